# rtl/units/trv.v: the traversal unit's datapath (split step and box clip, latency 4 * STAGES).
# Included by rtl/CMakeLists.txt (CMAKE_CURRENT_SOURCE_DIR is rtl/). Two libraries:
#   raycore_rtl_trv    --cc models, driven directly from C++ by tb/rtl/test_rtl_trv.cpp (bit-exact
#                      against hls::trv_split / hls::trv_clip_box);
#   raycore_rtl_trv_sc --sc models (sc_in/sc_out ports), bound beside the SystemC twin
#                      systemc/pins/trv.h in tb/rtl/test_lockstep_trv.cpp.
raycore_rtl_unit(trv VARIANTS
  "trv FP24 rtz 0"
  "trv FP24 rtz 2"
  "trv FP24 rne 1"
  "trv FP32 rne 2"
  "trv FP24 raycore 2")

# The --sc models need SystemC (pkg-config); without it the lockstep tests are left out.
find_package(PkgConfig QUIET)
if(PkgConfig_FOUND)
  pkg_check_modules(RAYCORE_TRV_SYSC QUIET systemc)
endif()
if(RAYCORE_TRV_SYSC_FOUND)
  raycore_rtl_library(raycore_rtl_trv_sc trv_sc SYSTEMC SOURCES ${RAYCORE_RTL_TRV_SOURCES} VARIANTS
    "trv FP24 rtz 1"
    "trv FP24 rne 2")
endif()

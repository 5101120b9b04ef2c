# rtl/units/membus_if.v: the memory bus interface (N request channels, round-robin, DEPTH
# outstanding, beats of BEAT_BYTES routed back). Included by rtl/CMakeLists.txt.
# Verilated --sc (library raycore_rtl_membus_if_sc) for tb/rtl/test_lockstep_membus_if.cpp, beside
# its SystemC twin systemc/pins/membus_if.h, with raycore_rtl_library()'s format-less form:
# include_membus_if_sc/rtl_membus_if_sc_models.h and _variants.h (one line
# RAYCORE_RTL_MEMBUS_IF_SC_VARIANT(prefix, N, ADDR_BITS, LEN_BITS, TAG_BITS, DEPTH, BEAT_BYTES)
# per variant), SYSTEM headers.
find_package(PkgConfig QUIET)
if(PkgConfig_FOUND)
  pkg_check_modules(RAYCORE_MEMBUS_IF_SYSC QUIET systemc)
endif()
if(RAYCORE_MEMBUS_IF_SYSC_FOUND)
  # Variants: "N ADDR_BITS LEN_BITS TAG_BITS DEPTH BEAT_BYTES" (one RTU with the default queue and
  # bus; two RTUs with a short queue and a narrow bus: queue-full and many beats per line).
  raycore_rtl_library(raycore_rtl_membus_if_sc membus_if_sc SYSTEMC
    SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/units/membus_if.v
    TOP membus_if PARAMS N ADDR_BITS LEN_BITS TAG_BITS DEPTH BEAT_BYTES
    PREFIX "Vmembus_if_n@N@_q@DEPTH@_b@BEAT_BYTES@"
    VARIANTS "3 32 12 8 32 16" "6 32 12 8 4 8")
endif()

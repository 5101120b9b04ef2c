# rtl/units/rgu.cmake - the ray generation unit (rtl/units/rgu*.v), for tb/rtl/test_rtl_rgu.cpp.
# Included by rtl/CMakeLists.txt (after find_package(verilator)). Two libraries of --cc models:
#   raycore_rtl_rgu      the datapath rgu_ray (latency 15 * STAGES), bit-exact against
#                        hls::rgu_primary on random cameras and pixels; variant lines
#                        RAYCORE_RTL_RGU_VARIANT(prefix, rgu_ray, fmt, mode, stages)
#   raycore_rtl_rgu_top  the unit rgu (pixel walk rgu_walk + rgu_ray): rays of whole frames in
#                        hls::RguTiles order; format-less form (the top has no TAG_BITS), lines
#                        RAYCORE_RTL_RGU_TOP_VARIANT(prefix, LABEL, EXP_BITS, MAN_BITS, RNE,
#                        RAYCORE, STAGES, TILE_BITS)
set(RAYCORE_RTL_RGU_SOURCES ${RAYCORE_RTL_FP_SOURCES})
foreach(m rgu_walk rgu_ray rgu)
  list(APPEND RAYCORE_RTL_RGU_SOURCES ${CMAKE_CURRENT_LIST_DIR}/${m}.v)
endforeach()
set(RAYCORE_RTL_RGU_SOURCES ${RAYCORE_RTL_RGU_SOURCES} CACHE INTERNAL "rtl/units/rgu*.v and rtl/fp")

raycore_rtl_library(raycore_rtl_rgu rgu SOURCES ${RAYCORE_RTL_RGU_SOURCES} VARIANTS
  "rgu_ray FP24 rtz 2"
  "rgu_ray FP24 rne 1"
  "rgu_ray FP32 rne 2"
  "rgu_ray FP24 raycore 2")

# FP24 rtz at STAGES 2 with 8 x 8 tiles (the cycle model's defaults); FP24 rne, combinational
# (STAGES 0), 4 x 4 tiles; FP24 raycore at STAGES 2, 8 x 8 tiles. The label names the rounding.
raycore_rtl_library(raycore_rtl_rgu_top rgu_top SOURCES ${RAYCORE_RTL_RGU_SOURCES}
  TOP rgu LABEL PARAMS EXP_BITS MAN_BITS RNE RAYCORE STAGES TILE_BITS
  PREFIX "Vrgu_e@EXP_BITS@m@MAN_BITS@_@LABEL@_s@STAGES@_t@TILE_BITS@" VARIANTS
  "rtz     7 16 0 0 2 3"
  "rne     7 16 1 0 0 2"
  "raycore 7 16 0 1 2 3")

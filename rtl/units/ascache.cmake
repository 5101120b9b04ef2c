# rtl/units/ascache.cmake - the AS cache (rtl/units/ascache*.v), verilated with --sc for the lockstep
# test against its SystemC twin systemc/pins/ascache.h (tb/rtl/test_lockstep_ascache.cpp).
# Included by rtl/CMakeLists.txt (after find_package(verilator)).
#
# raycore_rtl_library()'s format-less form (the cache has no number format; its geometry is its
# parameters): one static library of --sc models, prefix Vascache_<name>_sc, a header including all
# of them (rtl_ascache_models.h) and one line per variant (rtl_ascache_variants.h):
#   RAYCORE_RTL_ASCACHE_VARIANT(prefix, name, SETS, WAYS, LINE_BYTES, MSHRS, HIT_LATENCY)
set(RAYCORE_RTL_ASCACHE_SOURCES "")
foreach(m ascache_ram ascache_victim ascache_touch ascache)
  list(APPEND RAYCORE_RTL_ASCACHE_SOURCES ${CMAKE_CURRENT_LIST_DIR}/${m}.v)
endforeach()
set(RAYCORE_RTL_ASCACHE_SOURCES ${RAYCORE_RTL_ASCACHE_SOURCES} CACHE INTERNAL "rtl/units/ascache*.v")

# name SETS WAYS LINE_BYTES MSHRS HIT_LATENCY. 1k2w: 1 KB, 2 ways, 64 B lines, 4 MSHRs (small: MSHR
# full and evictions come often); 1k2w_l3: the same with 3 cycles of hit latency; 16k4w: the cycle
# model's node cache (16 KB, 4 ways, 64 B lines, 8 MSHRs). Line index 26 bits (32-bit byte
# addresses), 16-bit requester tag, 32-bit counters.
set(RAYCORE_RTL_ASCACHE_VARIANTS
  "1k2w    8 2 64 4 1"
  "1k2w_l3 8 2 64 4 3"
  "16k4w  64 4 64 8 1"
  CACHE INTERNAL "Verilated ascache variants")

raycore_rtl_library(raycore_rtl_ascache ascache SYSTEMC SOURCES ${RAYCORE_RTL_ASCACHE_SOURCES}
  TOP ascache LABEL PARAMS SETS WAYS LINE_BYTES MSHRS HIT_LATENCY
  FIXED LINE_W=26 TAG_BITS=16 CNT_BITS=32
  PREFIX "Vascache_@LABEL@" VARIANTS ${RAYCORE_RTL_ASCACHE_VARIANTS})

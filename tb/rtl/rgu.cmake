# tb/rtl/rgu.cmake - the ray generation unit's co-simulation (included by tb/rtl/CMakeLists.txt):
# rtl/units/rgu_ray.v against hls::rgu_primary and rtl/units/rgu.v (walk + datapath) against
# hls::RguTiles + hls::rgu_primary, Verilator --cc models driven from C++ (label "rtl").
if(TARGET raycore_rtl_rgu AND TARGET raycore_rtl_rgu_top)
  add_executable(test_rtl_rgu test_rtl_rgu.cpp)
  target_link_libraries(test_rtl_rgu PRIVATE raycore_rtl_rgu raycore_rtl_rgu_top raycore_hls
    raycore_warnings GTest::gtest GTest::gtest_main)
  gtest_discover_tests(test_rtl_rgu PROPERTIES LABELS "rtl" DISCOVERY_TIMEOUT 60)
endif()

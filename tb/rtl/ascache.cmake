# tb/rtl/ascache.cmake - the AS cache's lockstep test (included by tb/rtl/CMakeLists.txt): the
# SystemC twin (systemc/pins/ascache.h around raycore::sc::Ascache) and the Verilated RTL
# (rtl/units/ascache.v, --sc, library raycore_rtl_ascache from rtl/units/ascache.cmake) side by
# side, one test per variant, label "rtl". SystemC's main() calls sc_main: the binary defines
# sc_main (running the tests) and links gtest, not gtest_main; each test runs in its own process
# (one SystemC simulation per process). Ascache's one source file is compiled in, so the test
# does not need the whole cycle model (raycore_sc).
if(TARGET raycore_rtl_ascache)
  add_executable(test_lockstep_ascache test_lockstep_ascache.cpp
    ${CMAKE_SOURCE_DIR}/systemc/ascache.cpp)
  target_link_libraries(test_lockstep_ascache PRIVATE raycore_rtl_ascache raycore_hls
    raycore_warnings GTest::gtest)
  gtest_discover_tests(test_lockstep_ascache PROPERTIES LABELS "rtl"
    ENVIRONMENT "SYSTEMC_DISABLE_COPYRIGHT_MESSAGE=1" DISCOVERY_TIMEOUT 60)
endif()

# tb/rtl/trv.cmake (included by tb/rtl/CMakeLists.txt): the tests of rtl/units/trv.v and
# rtl/units/membus_if.v, label "rtl".
#   test_rtl_trv             Verilated --cc trv vs hls::trv_split / trv_clip_box, bit for bit
#                            (added by tb/rtl/CMakeLists.txt with the other units' test_rtl_*)
#   test_lockstep_trv        Verilated --sc trv beside its SystemC twin systemc/pins/trv.h
#   test_lockstep_membus_if  Verilated --sc membus_if beside systemc/pins/membus_if.h
# The lockstep tests link SystemC: each defines sc_main (calling InitGoogleTest) and links
# GTest::gtest, not gtest_main; one simulation per process (gtest_discover_tests).
foreach(unit trv membus_if)
  if(TARGET raycore_rtl_${unit}_sc AND EXISTS ${CMAKE_CURRENT_SOURCE_DIR}/test_lockstep_${unit}.cpp)
    add_executable(test_lockstep_${unit} test_lockstep_${unit}.cpp)
    target_link_libraries(test_lockstep_${unit} PRIVATE raycore_rtl_${unit}_sc raycore_hls
      raycore_warnings GTest::gtest)
    gtest_discover_tests(test_lockstep_${unit} PROPERTIES LABELS "rtl"
      ENVIRONMENT "SYSTEMC_DISABLE_COPYRIGHT_MESSAGE=1" DISCOVERY_TIMEOUT 60)
  endif()
endforeach()
# The membus_if test also runs the cycle model's bus (systemc/membus.cpp, self-contained: only
# SystemC and systemc/fifo.h) on the same requests.
if(TARGET test_lockstep_membus_if)
  target_sources(test_lockstep_membus_if PRIVATE ${CMAKE_SOURCE_DIR}/systemc/membus.cpp)
endif()

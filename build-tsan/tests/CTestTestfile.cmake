# CMake generated Testfile for 
# Source directory: /work/main/tests
# Build directory: /work/main/build-tsan/tests
# 
# This file includes the relevant testing commands required for 
# testing this directory and lists subdirectories to be tested as well.
include("/work/main/build-tsan/tests/vplgi_tests_cpu_include-b12d07c.cmake")
add_test([=[cpu: core links no GL]=] "bash" "/work/main/tests/cli/core_without_gl.sh" "/work/main/build-tsan/tests/vplgi_tests_cpu")
set_tests_properties([=[cpu: core links no GL]=] PROPERTIES  _BACKTRACE_TRIPLES "/work/main/tests/CMakeLists.txt;27;add_test;/work/main/tests/CMakeLists.txt;0;")

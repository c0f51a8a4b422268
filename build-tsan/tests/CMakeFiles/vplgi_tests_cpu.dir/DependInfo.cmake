
# Consider dependencies only in project.
set(CMAKE_DEPENDS_IN_PROJECT_ONLY OFF)

# The set of languages for which implicit dependencies are needed:
set(CMAKE_DEPENDS_LANGUAGES
  )

# The set of dependency files which are needed:
set(CMAKE_DEPENDS_DEPENDENCY_FILES
  "/work/main/tests/cpu/test_builtin_scenes.cpp" "tests/CMakeFiles/vplgi_tests_cpu.dir/cpu/test_builtin_scenes.cpp.o" "gcc" "tests/CMakeFiles/vplgi_tests_cpu.dir/cpu/test_builtin_scenes.cpp.o.d"
  "/work/main/tests/cpu/test_direct_lights.cpp" "tests/CMakeFiles/vplgi_tests_cpu.dir/cpu/test_direct_lights.cpp.o" "gcc" "tests/CMakeFiles/vplgi_tests_cpu.dir/cpu/test_direct_lights.cpp.o.d"
  "/work/main/tests/cpu/test_image_io.cpp" "tests/CMakeFiles/vplgi_tests_cpu.dir/cpu/test_image_io.cpp.o" "gcc" "tests/CMakeFiles/vplgi_tests_cpu.dir/cpu/test_image_io.cpp.o.d"
  "/work/main/tests/cpu/test_knn.cpp" "tests/CMakeFiles/vplgi_tests_cpu.dir/cpu/test_knn.cpp.o" "gcc" "tests/CMakeFiles/vplgi_tests_cpu.dir/cpu/test_knn.cpp.o.d"
  "/work/main/tests/cpu/test_metrics.cpp" "tests/CMakeFiles/vplgi_tests_cpu.dir/cpu/test_metrics.cpp.o" "gcc" "tests/CMakeFiles/vplgi_tests_cpu.dir/cpu/test_metrics.cpp.o.d"
  "/work/main/tests/cpu/test_params.cpp" "tests/CMakeFiles/vplgi_tests_cpu.dir/cpu/test_params.cpp.o" "gcc" "tests/CMakeFiles/vplgi_tests_cpu.dir/cpu/test_params.cpp.o.d"
  "/work/main/tests/cpu/test_path_tracer.cpp" "tests/CMakeFiles/vplgi_tests_cpu.dir/cpu/test_path_tracer.cpp.o" "gcc" "tests/CMakeFiles/vplgi_tests_cpu.dir/cpu/test_path_tracer.cpp.o.d"
  "/work/main/tests/cpu/test_ray_scene.cpp" "tests/CMakeFiles/vplgi_tests_cpu.dir/cpu/test_ray_scene.cpp.o" "gcc" "tests/CMakeFiles/vplgi_tests_cpu.dir/cpu/test_ray_scene.cpp.o.d"
  "/work/main/tests/cpu/test_scene.cpp" "tests/CMakeFiles/vplgi_tests_cpu.dir/cpu/test_scene.cpp.o" "gcc" "tests/CMakeFiles/vplgi_tests_cpu.dir/cpu/test_scene.cpp.o.d"
  "/work/main/tests/cpu/test_scene_loader.cpp" "tests/CMakeFiles/vplgi_tests_cpu.dir/cpu/test_scene_loader.cpp.o" "gcc" "tests/CMakeFiles/vplgi_tests_cpu.dir/cpu/test_scene_loader.cpp.o.d"
  "/work/main/tests/cpu/test_smcir_rt.cpp" "tests/CMakeFiles/vplgi_tests_cpu.dir/cpu/test_smcir_rt.cpp.o" "gcc" "tests/CMakeFiles/vplgi_tests_cpu.dir/cpu/test_smcir_rt.cpp.o.d"
  "/work/main/tests/cpu/test_smcir_sampler.cpp" "tests/CMakeFiles/vplgi_tests_cpu.dir/cpu/test_smcir_sampler.cpp.o" "gcc" "tests/CMakeFiles/vplgi_tests_cpu.dir/cpu/test_smcir_sampler.cpp.o.d"
  "/work/main/tests/cpu/test_smcir_worker.cpp" "tests/CMakeFiles/vplgi_tests_cpu.dir/cpu/test_smcir_worker.cpp.o" "gcc" "tests/CMakeFiles/vplgi_tests_cpu.dir/cpu/test_smcir_worker.cpp.o.d"
  "/work/main/tests/cpu/test_vpl_gather.cpp" "tests/CMakeFiles/vplgi_tests_cpu.dir/cpu/test_vpl_gather.cpp.o" "gcc" "tests/CMakeFiles/vplgi_tests_cpu.dir/cpu/test_vpl_gather.cpp.o.d"
  )

# Targets to which this target links.
set(CMAKE_TARGET_LINKED_INFO_FILES
  "/work/main/build-tsan/core/CMakeFiles/vplgi_core.dir/DependInfo.cmake"
  )

# Fortran module output directory.
set(CMAKE_Fortran_TARGET_MODULE_DIR "")

file(REMOVE_RECURSE
  "CMakeFiles/vplgi_tests_cpu.dir/cpu/test_builtin_scenes.cpp.o"
  "CMakeFiles/vplgi_tests_cpu.dir/cpu/test_builtin_scenes.cpp.o.d"
  "CMakeFiles/vplgi_tests_cpu.dir/cpu/test_direct_lights.cpp.o"
  "CMakeFiles/vplgi_tests_cpu.dir/cpu/test_direct_lights.cpp.o.d"
  "CMakeFiles/vplgi_tests_cpu.dir/cpu/test_image_io.cpp.o"
  "CMakeFiles/vplgi_tests_cpu.dir/cpu/test_image_io.cpp.o.d"
  "CMakeFiles/vplgi_tests_cpu.dir/cpu/test_knn.cpp.o"
  "CMakeFiles/vplgi_tests_cpu.dir/cpu/test_knn.cpp.o.d"
  "CMakeFiles/vplgi_tests_cpu.dir/cpu/test_metrics.cpp.o"
  "CMakeFiles/vplgi_tests_cpu.dir/cpu/test_metrics.cpp.o.d"
  "CMakeFiles/vplgi_tests_cpu.dir/cpu/test_params.cpp.o"
  "CMakeFiles/vplgi_tests_cpu.dir/cpu/test_params.cpp.o.d"
  "CMakeFiles/vplgi_tests_cpu.dir/cpu/test_path_tracer.cpp.o"
  "CMakeFiles/vplgi_tests_cpu.dir/cpu/test_path_tracer.cpp.o.d"
  "CMakeFiles/vplgi_tests_cpu.dir/cpu/test_ray_scene.cpp.o"
  "CMakeFiles/vplgi_tests_cpu.dir/cpu/test_ray_scene.cpp.o.d"
  "CMakeFiles/vplgi_tests_cpu.dir/cpu/test_scene.cpp.o"
  "CMakeFiles/vplgi_tests_cpu.dir/cpu/test_scene.cpp.o.d"
  "CMakeFiles/vplgi_tests_cpu.dir/cpu/test_scene_loader.cpp.o"
  "CMakeFiles/vplgi_tests_cpu.dir/cpu/test_scene_loader.cpp.o.d"
  "CMakeFiles/vplgi_tests_cpu.dir/cpu/test_smcir_rt.cpp.o"
  "CMakeFiles/vplgi_tests_cpu.dir/cpu/test_smcir_rt.cpp.o.d"
  "CMakeFiles/vplgi_tests_cpu.dir/cpu/test_smcir_sampler.cpp.o"
  "CMakeFiles/vplgi_tests_cpu.dir/cpu/test_smcir_sampler.cpp.o.d"
  "CMakeFiles/vplgi_tests_cpu.dir/cpu/test_smcir_worker.cpp.o"
  "CMakeFiles/vplgi_tests_cpu.dir/cpu/test_smcir_worker.cpp.o.d"
  "CMakeFiles/vplgi_tests_cpu.dir/cpu/test_vpl_gather.cpp.o"
  "CMakeFiles/vplgi_tests_cpu.dir/cpu/test_vpl_gather.cpp.o.d"
  "vplgi_tests_cpu"
  "vplgi_tests_cpu.pdb"
  "vplgi_tests_cpu_tests-b12d07c.cmake"
)

# Per-language clean rules from dependency scanning.
foreach(lang CXX)
  include(CMakeFiles/vplgi_tests_cpu.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()

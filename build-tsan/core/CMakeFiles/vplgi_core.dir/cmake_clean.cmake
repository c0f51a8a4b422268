file(REMOVE_RECURSE
  "CMakeFiles/vplgi_core.dir/builtin_scenes.cpp.o"
  "CMakeFiles/vplgi_core.dir/builtin_scenes.cpp.o.d"
  "CMakeFiles/vplgi_core.dir/content_hash.cpp.o"
  "CMakeFiles/vplgi_core.dir/content_hash.cpp.o.d"
  "CMakeFiles/vplgi_core.dir/direct_lights.cpp.o"
  "CMakeFiles/vplgi_core.dir/direct_lights.cpp.o.d"
  "CMakeFiles/vplgi_core.dir/image_io.cpp.o"
  "CMakeFiles/vplgi_core.dir/image_io.cpp.o.d"
  "CMakeFiles/vplgi_core.dir/knn.cpp.o"
  "CMakeFiles/vplgi_core.dir/knn.cpp.o.d"
  "CMakeFiles/vplgi_core.dir/metrics.cpp.o"
  "CMakeFiles/vplgi_core.dir/metrics.cpp.o.d"
  "CMakeFiles/vplgi_core.dir/params.cpp.o"
  "CMakeFiles/vplgi_core.dir/params.cpp.o.d"
  "CMakeFiles/vplgi_core.dir/path_tracer.cpp.o"
  "CMakeFiles/vplgi_core.dir/path_tracer.cpp.o.d"
  "CMakeFiles/vplgi_core.dir/ray_scene.cpp.o"
  "CMakeFiles/vplgi_core.dir/ray_scene.cpp.o.d"
  "CMakeFiles/vplgi_core.dir/scene.cpp.o"
  "CMakeFiles/vplgi_core.dir/scene.cpp.o.d"
  "CMakeFiles/vplgi_core.dir/scene_loader.cpp.o"
  "CMakeFiles/vplgi_core.dir/scene_loader.cpp.o.d"
  "CMakeFiles/vplgi_core.dir/smcir_sampler.cpp.o"
  "CMakeFiles/vplgi_core.dir/smcir_sampler.cpp.o.d"
  "CMakeFiles/vplgi_core.dir/smcir_worker.cpp.o"
  "CMakeFiles/vplgi_core.dir/smcir_worker.cpp.o.d"
  "CMakeFiles/vplgi_core.dir/surface.cpp.o"
  "CMakeFiles/vplgi_core.dir/surface.cpp.o.d"
  "CMakeFiles/vplgi_core.dir/vpl_gather.cpp.o"
  "CMakeFiles/vplgi_core.dir/vpl_gather.cpp.o.d"
  "libvplgi_core.a"
  "libvplgi_core.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang CXX)
  include(CMakeFiles/vplgi_core.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()

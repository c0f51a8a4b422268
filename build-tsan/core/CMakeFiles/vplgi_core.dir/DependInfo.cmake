
# Consider dependencies only in project.
set(CMAKE_DEPENDS_IN_PROJECT_ONLY OFF)

# The set of languages for which implicit dependencies are needed:
set(CMAKE_DEPENDS_LANGUAGES
  )

# The set of dependency files which are needed:
set(CMAKE_DEPENDS_DEPENDENCY_FILES
  "/work/main/core/builtin_scenes.cpp" "core/CMakeFiles/vplgi_core.dir/builtin_scenes.cpp.o" "gcc" "core/CMakeFiles/vplgi_core.dir/builtin_scenes.cpp.o.d"
  "/work/main/core/content_hash.cpp" "core/CMakeFiles/vplgi_core.dir/content_hash.cpp.o" "gcc" "core/CMakeFiles/vplgi_core.dir/content_hash.cpp.o.d"
  "/work/main/core/direct_lights.cpp" "core/CMakeFiles/vplgi_core.dir/direct_lights.cpp.o" "gcc" "core/CMakeFiles/vplgi_core.dir/direct_lights.cpp.o.d"
  "/work/main/core/image_io.cpp" "core/CMakeFiles/vplgi_core.dir/image_io.cpp.o" "gcc" "core/CMakeFiles/vplgi_core.dir/image_io.cpp.o.d"
  "/work/main/core/knn.cpp" "core/CMakeFiles/vplgi_core.dir/knn.cpp.o" "gcc" "core/CMakeFiles/vplgi_core.dir/knn.cpp.o.d"
  "/work/main/core/metrics.cpp" "core/CMakeFiles/vplgi_core.dir/metrics.cpp.o" "gcc" "core/CMakeFiles/vplgi_core.dir/metrics.cpp.o.d"
  "/work/main/core/params.cpp" "core/CMakeFiles/vplgi_core.dir/params.cpp.o" "gcc" "core/CMakeFiles/vplgi_core.dir/params.cpp.o.d"
  "/work/main/core/path_tracer.cpp" "core/CMakeFiles/vplgi_core.dir/path_tracer.cpp.o" "gcc" "core/CMakeFiles/vplgi_core.dir/path_tracer.cpp.o.d"
  "/work/main/core/ray_scene.cpp" "core/CMakeFiles/vplgi_core.dir/ray_scene.cpp.o" "gcc" "core/CMakeFiles/vplgi_core.dir/ray_scene.cpp.o.d"
  "/work/main/core/scene.cpp" "core/CMakeFiles/vplgi_core.dir/scene.cpp.o" "gcc" "core/CMakeFiles/vplgi_core.dir/scene.cpp.o.d"
  "/work/main/core/scene_loader.cpp" "core/CMakeFiles/vplgi_core.dir/scene_loader.cpp.o" "gcc" "core/CMakeFiles/vplgi_core.dir/scene_loader.cpp.o.d"
  "/work/main/core/smcir_sampler.cpp" "core/CMakeFiles/vplgi_core.dir/smcir_sampler.cpp.o" "gcc" "core/CMakeFiles/vplgi_core.dir/smcir_sampler.cpp.o.d"
  "/work/main/core/smcir_worker.cpp" "core/CMakeFiles/vplgi_core.dir/smcir_worker.cpp.o" "gcc" "core/CMakeFiles/vplgi_core.dir/smcir_worker.cpp.o.d"
  "/work/main/core/surface.cpp" "core/CMakeFiles/vplgi_core.dir/surface.cpp.o" "gcc" "core/CMakeFiles/vplgi_core.dir/surface.cpp.o.d"
  "/work/main/core/vpl_gather.cpp" "core/CMakeFiles/vplgi_core.dir/vpl_gather.cpp.o" "gcc" "core/CMakeFiles/vplgi_core.dir/vpl_gather.cpp.o.d"
  )

# Targets to which this target links.
set(CMAKE_TARGET_LINKED_INFO_FILES
  )

# Fortran module output directory.
set(CMAKE_Fortran_TARGET_MODULE_DIR "")

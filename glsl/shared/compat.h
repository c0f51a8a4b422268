// Lets a header be compiled as both GLSL 4.50 and C++17 (with GLM).
// Every shared header has an #ifndef guard (works in both languages) and marks functions
// VPLGI_FUNC (inline in C++).
// Rules for shared code: float literals carry an `f` suffix, output parameters only through
// VPLGI_OUT(type) (`out type` in GLSL, `type&` in C++; no `inout`), no swizzle writes, no arrays; structs hold vec4/uvec4/float/int members so std140/std430 and
// C++ layouts agree (checked by static_asserts here and by a GL test against the driver's offsets).
#ifdef __cplusplus
#pragma once
#include <cstdint>
#include <glm/glm.hpp>
#define VPLGI_SHARED_BEGIN namespace vplgi::shared { using namespace glm;
#define VPLGI_SHARED_END }
#define VPLGI_CONST constexpr
#define VPLGI_FUNC inline
#define VPLGI_OUT(type) type&
#else
#define VPLGI_SHARED_BEGIN
#define VPLGI_SHARED_END
#define VPLGI_CONST const
#define VPLGI_FUNC
#define VPLGI_OUT(type) out type
#endif

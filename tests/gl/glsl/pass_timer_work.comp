#version 450 core
// Real GPU work for the pass-timer test: writes a gradient into a small image.
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, rgba8) uniform writeonly image2D target;

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    imageStore(target, p, vec4(vec2(p) / vec2(imageSize(target)), 0.5, 1.0));
}

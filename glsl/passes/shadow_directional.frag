#version 450 core
// Directional shadow maps keep the rasterized depth; nothing to write.
void main()
{
}

#version 450 core
// The shadow atlas keeps the rasterized depth (DEPTH32F, the same window-space depth as the view
// rendered alone); nothing to write, so the rasterizer can test and write depth early.
void main()
{
}

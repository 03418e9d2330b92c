#version 460

// Depth only: the rasteriser writes the depth, nothing else is stored.
void main() {}

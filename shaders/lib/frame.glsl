// Binding 0 of set 0 in every pass: the frame's constants.
#ifndef RAYSTER_FRAME_GLSL
#define RAYSTER_FRAME_GLSL
layout(set = 0, binding = 0, scalar) uniform FrameBlock { FrameConstants frame; };
#endif

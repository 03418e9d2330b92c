#pragma once
// Sub-pixel jitter for TAA (docs/techniques.md §18): a Halton(2,3) sequence of period kJitterPeriod.
//
// Units: NDC spans 2 across `width` pixels, so one pixel is 2/width in NDC. The offset
// jx = (2·h2 − 1)/width = (h2 − 0.5)·2/width is therefore (h2 − 0.5) pixels: within ±0.5 px,
// never ±1 px. Same for y with h3 and height.
#include <cstdint>

#include <glm/glm.hpp>

namespace rayster::render {

// 4 positions resolve edges coarsely (the book's period); 16 gives 16 distinct sub-pixel positions.
inline constexpr uint32_t kJitterPeriod = 16;

// The radical inverse of `index` in `base` (the Halton sequence's element), in [0, 1).
float halton(uint32_t index, uint32_t base);

// The offset of frame `frame` in pixels, in [−0.5, 0.5)². Index 0 of the sequence (0, 0) is
// skipped, so the first frame samples (0, −1/6) px rather than a pixel corner.
glm::vec2 jitterPixels(uint32_t frame);

// The same offset in NDC for a width × height image: add it to clip x, y per unit w.
glm::vec2 jitterNdc(uint32_t frame, uint32_t width, uint32_t height);

// clipFromWorld with the NDC offset applied: a translation in NDC after the projection
// (equivalent to adding it to the projection's third column with the sign of w = −z_view).
glm::mat4 jitteredClipFromWorld(const glm::mat4& clipFromWorld, glm::vec2 ndcOffset);
glm::dmat4 jitteredClipFromWorld(const glm::dmat4& clipFromWorld, glm::dvec2 ndcOffset);

}  // namespace rayster::render

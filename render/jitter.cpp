#include "render/jitter.h"

namespace rayster::render {

float halton(uint32_t index, uint32_t base) {
  float f = 1.0f, r = 0.0f;
  for (uint32_t i = index; i > 0; i /= base) {
    f /= float(base);
    r += f * float(i % base);
  }
  return r;
}

glm::vec2 jitterPixels(uint32_t frame) {
  const uint32_t i = frame % kJitterPeriod + 1;
  return {halton(i, 2) - 0.5f, halton(i, 3) - 0.5f};
}

glm::vec2 jitterNdc(uint32_t frame, uint32_t width, uint32_t height) {
  const glm::vec2 px = jitterPixels(frame);
  return {px.x * 2.0f / float(width), px.y * 2.0f / float(height)};
}

namespace {
template <class Mat, class Vec>
Mat jittered(const Mat& clipFromWorld, Vec ndcOffset) {
  Mat t(1);
  t[3][0] = ndcOffset.x;  // clip.x += jx·w, so ndc.x += jx
  t[3][1] = ndcOffset.y;
  return t * clipFromWorld;
}
}  // namespace

glm::mat4 jitteredClipFromWorld(const glm::mat4& clipFromWorld, glm::vec2 ndcOffset) {
  return jittered(clipFromWorld, ndcOffset);
}
glm::dmat4 jitteredClipFromWorld(const glm::dmat4& clipFromWorld, glm::dvec2 ndcOffset) {
  return jittered(clipFromWorld, ndcOffset);
}

}  // namespace rayster::render

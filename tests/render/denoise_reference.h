#pragma once
// CPU reference of the denoiser kernels (shaders/surface.comp, shadow_*.comp, svgf_*.comp and
// shaders/lib/denoise.glsl), written from the same formulas and the same shared constants, for
// tests/render/test_denoise.cpp. Images are float vectors, layer-major then row-major.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "shaders/shared/denoise.h"

namespace rayster::test::ref {

using glm::ivec2;
using glm::vec2;
using glm::vec3;
using glm::vec4;

struct Surf {
  float z = 0, zGrad = 0;
  vec3 n{0.0f};
  uint32_t id = gpu::kBackgroundId;
  bool sharp = false;  // mirror or glass: roughness ≤ kSharpRoughness (the depth's sign bit)
  bool sky() const { return id == gpu::kBackgroundId; }
};

inline vec2 octEncode(vec3 n) {
  vec2 p = vec2(n.x, n.y) / (std::abs(n.x) + std::abs(n.y) + std::abs(n.z));
  if (n.z >= 0) return p;
  return (1.0f - glm::abs(vec2(p.y, p.x))) * vec2(p.x >= 0 ? 1.0f : -1.0f, p.y >= 0 ? 1.0f : -1.0f);
}
inline vec3 octDecode(vec2 e) {
  vec3 n(e.x, e.y, 1.0f - std::abs(e.x) - std::abs(e.y));
  float t = std::max(-n.z, 0.0f);
  n.x += n.x >= 0 ? -t : t;
  n.y += n.y >= 0 ? -t : t;
  return glm::normalize(n);
}
inline float snorm16(int16_t v) { return std::clamp(v / 32767.0f, -1.0f, 1.0f); }
inline float snorm10(int v) { return std::clamp(v / 511.0f, -1.0f, 1.0f); }
inline int toSnorm10(float v) { return int(std::lround(std::clamp(v, -1.0f, 1.0f) * 511.0f)); }
inline int signExtend10(uint32_t v) { return int(v & 0x3FFu) - (v & 0x200u ? 1024 : 0); }

// The surface texel (RG32UI): z float bits (0: sky) | sharp in the sign bit; oct normal 2 × snorm10 |
// id's low 12 bits.
inline Surf decodeTexel(const uint32_t* t) {
  Surf s;
  s.z = std::bit_cast<float>(t[0] & 0x7FFFFFFFu);
  s.sharp = (t[0] >> 31) != 0;
  s.n = octDecode(vec2(snorm10(signExtend10(t[1])), snorm10(signExtend10(t[1] >> 10))));
  s.id = t[0] == 0 ? gpu::kBackgroundId : t[1] >> 20;
  return s;
}
// The depth slope |dz/dx| + |dz/dy| by one-sided differences, the smaller of each pair (so a
// silhouette beside the pixel does not pass for a steep slope); 0 where no neighbour is geometry.
inline void addSlopes(std::vector<Surf>& s, int w, int h) {
  auto on = [&](int x, int y) { return x >= 0 && y >= 0 && x < w && y < h && !s[size_t(y) * w + x].sky(); };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      Surf& c = s[size_t(y) * w + x];
      if (c.sky()) continue;
      auto slope = [&](int dx, int dy) {
        float best = 1e30f;
        if (on(x + dx, y + dy)) best = std::min(best, std::abs(s[size_t(y + dy) * w + x + dx].z - c.z));
        if (on(x - dx, y - dy)) best = std::min(best, std::abs(s[size_t(y - dy) * w + x - dx].z - c.z));
        return best < 1e30f ? best : 0.0f;
      };
      c.zGrad = slope(1, 0) + slope(0, 1);
    }
}
// A whole surface image (2 words per texel), with the slopes the shaders recompute.
inline std::vector<Surf> decodeSurfaces(const uint32_t* texels, int w, int h) {
  std::vector<Surf> s(size_t(w) * h);
  for (size_t i = 0; i < s.size(); ++i) s[i] = decodeTexel(texels + i * 2);
  addSlopes(s, w, h);
  return s;
}

// surface.comp: from reversed-Z depth, oct normals (snorm16 xy) and ids.
struct GBufferCpu {
  int w = 0, h = 0;
  std::vector<float> depth;
  std::vector<int16_t> normals;  // 4 per pixel
  std::vector<uint32_t> id;
  std::vector<uint8_t> material;  // 4 per pixel, .r roughness
};
inline float linearDepth(float d, float zNear, float zFar) { return zNear * zFar / (zNear + d * (zFar - zNear)); }
inline std::vector<Surf> surfaces(const GBufferCpu& g, float zNear, float zFar) {
  std::vector<Surf> out(size_t(g.w) * g.h);
  for (size_t i = 0; i < out.size(); ++i) {
    Surf& s = out[i];
    if (g.id[i] == gpu::kBackgroundId) continue;
    s.id = g.id[i] & 0xFFFu;
    s.z = linearDepth(g.depth[i], zNear, zFar);
    s.sharp = g.material[i * 4] / 255.0f <= gpu::kSharpRoughness;
    s.n = octDecode(
        vec2(snorm10(toSnorm10(snorm16(g.normals[i * 4]))), snorm10(toSnorm10(snorm16(g.normals[i * 4 + 1])))));
  }
  addSlopes(out, g.w, g.h);
  return out;
}

inline bool sameSurface(const Surf& cur, const Surf& prev) {
  if (prev.id != cur.id) return false;
  float tol = gpu::kReprojectDepthRelative * cur.z + gpu::kReprojectDepthSlopes * std::max(cur.zGrad, prev.zGrad);
  return std::abs(cur.z - prev.z) <= tol && glm::dot(cur.n, prev.n) >= gpu::kReprojectNormalDot;
}

struct Reproj {
  ivec2 tap[4];
  float w[4] = {0, 0, 0, 0};
  float sum = 0;
  bool valid() const { return sum >= gpu::kReprojectMinWeight; }
};
inline Reproj reproject(const std::vector<Surf>& prev, int w, int h, ivec2 px, vec2 motion, const Surf& cur) {
  Reproj r;
  vec2 pos = vec2(px) + 0.5f - motion * vec2(w, h) - 0.5f;
  ivec2 base = ivec2(glm::floor(pos));
  vec2 f = pos - vec2(base);
  for (int k = 0; k < 4; ++k) {
    ivec2 o(k & 1, k >> 1);
    r.tap[k] = base + o;
    float wt = (o.x ? f.x : 1 - f.x) * (o.y ? f.y : 1 - f.y);
    bool inside = r.tap[k].x >= 0 && r.tap[k].y >= 0 && r.tap[k].x < w && r.tap[k].y < h;
    if (wt <= 0 || !inside || !sameSurface(cur, prev[r.tap[k].y * w + r.tap[k].x])) wt = 0;
    r.w[k] = wt;
    r.sum += wt;
  }
  return r;
}

inline float b3(int i) { return i == 0 ? 0.375f : (std::abs(i) == 1 ? 0.25f : 0.0625f); }
inline float geometryWeight(const Surf& p, const Surf& q, vec2 offset) {
  float wz = std::exp(-std::abs(p.z - q.z) / (gpu::kSigmaDepth * p.zGrad * glm::length(offset) + gpu::kDepthEpsilon));
  float wn = std::pow(std::max(0.0f, glm::dot(p.n, q.n)), gpu::kSigmaNormal);
  return wz * wn;
}
inline float luminance(vec3 c) { return glm::dot(c, vec3(0.2126f, 0.7152f, 0.0722f)); }

struct Frame {
  int w, h;
  const std::vector<Surf>& cur;
  const std::vector<Surf>& prev;
  const std::vector<vec2>& motion;
  uint32_t flags;
  bool moving() const { return flags & gpu::kDenoiseMoving; }
  bool reset() const { return flags & gpu::kDenoiseReset; }
  bool inside(ivec2 q) const { return q.x >= 0 && q.y >= 0 && q.x < w && q.y < h; }
  size_t at(ivec2 q, int layer = 0) const { return (size_t(layer) * h + q.y) * w + q.x; }
  Reproj reprojectAt(ivec2 p) const {
    const Surf& s = cur[at(p)];
    if (s.sky() || reset()) return {};
    return reproject(prev, w, h, p, motion[at(p)], s);
  }
};

// shadow_temporal.comp: raw L layers, history L+1 layers (last: n) → L+1 layers, and the
// variance (L layers).
inline std::vector<float> shadowTemporal(const Frame& f, const std::vector<float>& raw, const std::vector<float>& hist,
                                         int layers, std::vector<float>* variance = nullptr) {
  std::vector<float> out(size_t(f.w) * f.h * (layers + 1)), var(size_t(f.w) * f.h * layers);
  for (int y = 0; y < f.h; ++y)
    for (int x = 0; x < f.w; ++x) {
      ivec2 p(x, y);
      Reproj r = f.reprojectAt(p);
      float n = 0;
      if (r.valid()) {
        for (int k = 0; k < 4; ++k)
          if (r.w[k] > 0) n += r.w[k] * hist[f.at(r.tap[k], layers)];
        n /= r.sum;
      }
      float alpha = std::max(1.0f / (1.0f + n), f.moving() ? gpu::kShadowAlphaMinMoving : 0.0f);
      const float nOut = r.valid() ? std::min(n + 1.0f, gpu::kShadowMaxLength) : 1.0f;
      const Surf& cur = f.cur[f.at(p)];
      const bool spatial = nOut < gpu::kShadowMinTemporalVarianceLength && !cur.sky();
      float sw[9];
      for (int k = 0; k < 9; ++k) {
        ivec2 o(k % 3 - 1, k / 3 - 1), q = p + o;
        sw[k] = 0;
        if (!spatial || !f.inside(q) || f.cur[f.at(q)].sky()) continue;
        sw[k] = k == 4 ? 1.0f : geometryWeight(cur, f.cur[f.at(q)], vec2(o));
      }
      for (int l = 0; l < layers; ++l) {
        float fresh = raw[f.at(p, l)], value = fresh;
        if (r.valid()) {
          float hv = 0;
          for (int k = 0; k < 4; ++k)
            if (r.w[k] > 0) hv += r.w[k] * hist[f.at(r.tap[k], l)];
          hv /= r.sum;
          if (f.moving()) {
            float lo = 1e30f, hi = -1e30f;
            for (int j = -1; j <= 1; ++j)
              for (int i = -1; i <= 1; ++i) {
                ivec2 q = glm::clamp(p + ivec2(i, j), ivec2(0), ivec2(f.w - 1, f.h - 1));
                lo = std::min(lo, raw[f.at(q, l)]);
                hi = std::max(hi, raw[f.at(q, l)]);
              }
            hv = std::clamp(hv, lo, hi);
          }
          value = hv + (fresh - hv) * alpha;
        }
        out[f.at(p, l)] = value;
        float m = value;
        if (spatial) {
          float sum = 0, weights = 0;
          for (int k = 0; k < 9; ++k) {
            if (sw[k] <= 0) continue;
            sum += sw[k] * raw[f.at(p + ivec2(k % 3 - 1, k / 3 - 1), l)];
            weights += sw[k];
          }
          m = sum / weights;
        }
        m = std::clamp(m, 0.0f, 1.0f);
        float v = cur.sky() ? 0.0f : m * (1 - m);
        if (!f.moving()) v /= nOut;
        var[f.at(p, l)] = v;
      }
      out[f.at(p, layers)] = nOut;
    }
  if (variance) *variance = var;
  return out;
}

// shadow_atrous.comp, one iteration.
inline std::vector<float> shadowAtrous(const Frame& f, const std::vector<float>& in, const std::vector<float>& var,
                                       int layers, int step) {
  std::vector<float> out(size_t(f.w) * f.h * layers);
  for (int y = 0; y < f.h; ++y)
    for (int x = 0; x < f.w; ++x) {
      ivec2 p(x, y);
      const Surf& sp = f.cur[f.at(p)];
      std::vector<float> sum(layers), weights(layers, 1.0f), centre(layers), scale(layers);
      for (int l = 0; l < layers; ++l) {
        centre[l] = sum[l] = in[f.at(p, l)];
        scale[l] = 1.0f / (gpu::kSigmaLuminance * std::sqrt(var[f.at(p, l)]) + gpu::kShadowValueEpsilon);
      }
      if (!sp.sky()) {
        std::fill(sum.begin(), sum.end(), 0.0f);
        std::fill(weights.begin(), weights.end(), 0.0f);
        for (int j = -2; j <= 2; ++j)
          for (int i = -2; i <= 2; ++i) {
            ivec2 q = p + step * ivec2(i, j);
            if (!f.inside(q) || f.cur[f.at(q)].sky()) continue;
            const bool isCentre = i == 0 && j == 0;
            float w = b3(i) * b3(j) * (isCentre ? 1.0f : geometryWeight(sp, f.cur[f.at(q)], vec2(step * i, step * j)));
            if (w <= 0) continue;
            for (int l = 0; l < layers; ++l) {
              float v = in[f.at(q, l)];
              float wl = isCentre ? w : w * std::exp(-std::abs(centre[l] - v) * scale[l]);
              sum[l] += wl * v;
              weights[l] += wl;
            }
          }
      }
      for (int l = 0; l < layers; ++l) out[f.at(p, l)] = sum[l] / weights[l];
    }
  return out;
}

// svgf_temporal.comp: raw RGBA, colour history (rgb, n), moments history (μ1, μ2) → colour (rgb,
// n), moments, and the working image (rgb colour, a variance).
inline void svgfTemporal(const Frame& f, const std::vector<vec4>& raw, const std::vector<vec4>& colorHist,
                         const std::vector<vec2>& momentsHist, std::vector<vec4>& color, std::vector<vec2>& moments,
                         std::vector<vec4>& working) {
  color.assign(raw.size(), vec4(0));
  moments.assign(raw.size(), vec2(0));
  working.assign(raw.size(), vec4(0));
  for (int y = 0; y < f.h; ++y)
    for (int x = 0; x < f.w; ++x) {
      ivec2 p(x, y);
      vec3 fresh = vec3(raw[f.at(p)]);
      float l = luminance(fresh);
      Reproj r = f.reprojectAt(p);
      vec3 c = fresh;
      vec2 m(l, l * l);
      float n = 1.0f;
      if (r.valid()) {
        vec4 ch(0);
        vec2 mh(0);
        for (int k = 0; k < 4; ++k) {
          if (r.w[k] <= 0) continue;
          ch += r.w[k] * colorHist[f.at(r.tap[k])];
          mh += r.w[k] * momentsHist[f.at(r.tap[k])];
        }
        ch /= r.sum;
        mh /= r.sum;
        n = std::min(ch.a + 1.0f, f.moving() ? gpu::kSvgfMaxLengthMoving : gpu::kSvgfMaxLengthStatic);
        float alpha = std::max(1.0f / n, f.moving() ? gpu::kSvgfAlphaMinMoving : 0.0f);
        c = vec3(ch) + (fresh - vec3(ch)) * alpha;
        m = mh + (vec2(l, l * l) - mh) * alpha;
      }
      color[f.at(p)] = vec4(c, n);
      moments[f.at(p)] = m;

      // Variance: temporal, or from the centre's moments and its 7×7 neighbours' samples.
      const Surf& sp = f.cur[f.at(p)];
      vec2 mu = m;
      if (n < gpu::kSvgfMinTemporalVarianceLength && !sp.sky()) {
        vec2 sum = m;
        float weights = 1.0f;
        for (int j = -gpu::kSvgfVarianceRadius; j <= gpu::kSvgfVarianceRadius; ++j)
          for (int i = -gpu::kSvgfVarianceRadius; i <= gpu::kSvgfVarianceRadius; ++i) {
            ivec2 q = p + ivec2(i, j);
            if ((i == 0 && j == 0) || !f.inside(q) || f.cur[f.at(q)].sky()) continue;
            float w = geometryWeight(sp, f.cur[f.at(q)], vec2(i, j));
            float lq = luminance(vec3(raw[f.at(q)]));
            sum += w * vec2(lq, lq * lq);
            weights += w;
          }
        mu = sum / weights;
      }
      float var = std::max(0.0f, mu.y - mu.x * mu.x);
      if (!f.moving()) var /= n;
      var = std::min(var, gpu::kSvgfMaxVariance);
      working[f.at(p)] = vec4(c, var);
    }
}

// svgf_atrous.comp, one iteration; roughness per pixel in [0, 1].
inline std::vector<vec4> svgfAtrous(const Frame& f, const std::vector<vec4>& in, const std::vector<float>& roughness,
                                    int step) {
  std::vector<vec4> out(in.size());
  auto sharp = [&](ivec2 q) { return roughness[f.at(q)] <= gpu::kSharpRoughness; };
  for (int y = 0; y < f.h; ++y)
    for (int x = 0; x < f.w; ++x) {
      ivec2 p(x, y);
      vec4 centre = in[f.at(p)];
      const Surf& sp = f.cur[f.at(p)];
      vec4 result = centre;
      if (!sp.sky() && !sharp(p)) {
        float gs = 0, gw = 0;
        for (int j = -1; j <= 1; ++j)
          for (int i = -1; i <= 1; ++i) {
            ivec2 q = p + ivec2(i, j);
            if (!f.inside(q)) continue;
            float w = (i == 0 ? 0.5f : 0.25f) * (j == 0 ? 0.5f : 0.25f);
            gs += w * in[f.at(q)].a;
            gw += w;
          }
        float lp = luminance(vec3(centre));
        float lumScale = 1.0f / (gpu::kSigmaLuminance * std::sqrt(gs / gw) + gpu::kLuminanceEpsilon);
        vec3 color(0);
        float var = 0, weights = 0;
        for (int j = -2; j <= 2; ++j)
          for (int i = -2; i <= 2; ++i) {
            ivec2 q = p + step * ivec2(i, j);
            if (!f.inside(q)) continue;
            vec4 c = in[f.at(q)];
            float w = b3(i) * b3(j);
            if (i != 0 || j != 0) {
              const Surf& sq = f.cur[f.at(q)];
              if (sq.sky() || sharp(q)) continue;
              w *= geometryWeight(sp, sq, vec2(step * i, step * j)) *
                   std::exp(-std::abs(lp - luminance(vec3(c))) * lumScale);
            }
            color += w * vec3(c);
            var += w * w * c.a;
            weights += w;
          }
        result = vec4(color / weights, var / (weights * weights));
      }
      out[f.at(p)] = result;
    }
  return out;
}

}  // namespace rayster::test::ref

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

inline Surf decodeSurface(const uint32_t* t) {
  Surf s;
  s.z = std::bit_cast<float>(t[0]);
  s.zGrad = std::bit_cast<float>(t[1]);
  s.n = octDecode(vec2(snorm16(int16_t(t[2] & 0xFFFFu)), snorm16(int16_t(t[2] >> 16))));
  s.id = t[3];
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
  auto on = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < g.w && y < g.h && g.id[y * g.w + x] != gpu::kBackgroundId;
  };
  auto z = [&](int x, int y) { return linearDepth(g.depth[y * g.w + x], zNear, zFar); };
  for (int y = 0; y < g.h; ++y)
    for (int x = 0; x < g.w; ++x) {
      Surf& s = out[y * g.w + x];
      s.id = g.id[y * g.w + x];
      if (s.sky()) continue;
      s.z = z(x, y);
      auto slope = [&](int dx, int dy) {
        float best = 1e30f;
        if (on(x + dx, y + dy)) best = std::min(best, std::abs(z(x + dx, y + dy) - s.z));
        if (on(x - dx, y - dy)) best = std::min(best, std::abs(z(x - dx, y - dy) - s.z));
        return best < 1e30f ? best : 0.0f;
      };
      s.zGrad = slope(1, 0) + slope(0, 1);
      s.n = octDecode(vec2(snorm16(g.normals[(y * g.w + x) * 4]), snorm16(g.normals[(y * g.w + x) * 4 + 1])));
    }
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

// svgf_temporal.comp: raw RGBA, colour history RGBA, moments history (μ1, μ2, n, -) → colour, moments.
inline void svgfTemporal(const Frame& f, const std::vector<vec4>& raw, const std::vector<vec4>& colorHist,
                         const std::vector<vec4>& momentsHist, std::vector<vec4>& color, std::vector<vec4>& moments) {
  color.assign(raw.size(), vec4(0));
  moments.assign(raw.size(), vec4(0));
  for (int y = 0; y < f.h; ++y)
    for (int x = 0; x < f.w; ++x) {
      ivec2 p(x, y);
      vec4 fresh = raw[f.at(p)];
      float l = luminance(vec3(fresh));
      Reproj r = f.reprojectAt(p);
      vec4 c = fresh;
      vec3 m(l, l * l, 1.0f);
      if (r.valid()) {
        vec4 ch(0);
        vec3 mh(0);
        for (int k = 0; k < 4; ++k) {
          if (r.w[k] <= 0) continue;
          ch += r.w[k] * colorHist[f.at(r.tap[k])];
          mh += r.w[k] * vec3(momentsHist[f.at(r.tap[k])]);
        }
        ch /= r.sum;
        mh /= r.sum;
        float n = std::min(mh.z + 1.0f, f.moving() ? gpu::kSvgfMaxLengthMoving : gpu::kSvgfMaxLengthStatic);
        float alpha = std::max(1.0f / n, f.moving() ? gpu::kSvgfAlphaMinMoving : 0.0f);
        c = ch + (fresh - ch) * alpha;
        vec2 mm = vec2(mh) + (vec2(l, l * l) - vec2(mh)) * alpha;
        m = vec3(mm, n);
      }
      color[f.at(p)] = c;
      moments[f.at(p)] = vec4(m, 0);
    }
}

// svgf_variance.comp → rgb colour, a variance.
inline std::vector<vec4> svgfVariance(const Frame& f, const std::vector<vec4>& color,
                                      const std::vector<vec4>& moments) {
  std::vector<vec4> out(color.size());
  for (int y = 0; y < f.h; ++y)
    for (int x = 0; x < f.w; ++x) {
      ivec2 p(x, y);
      vec3 m = vec3(moments[f.at(p)]);
      const Surf& sp = f.cur[f.at(p)];
      vec2 mu(m);
      if (m.z < gpu::kSvgfMinTemporalVarianceLength && !sp.sky()) {
        vec2 sum(0);
        float weights = 0;
        for (int j = -gpu::kSvgfVarianceRadius; j <= gpu::kSvgfVarianceRadius; ++j)
          for (int i = -gpu::kSvgfVarianceRadius; i <= gpu::kSvgfVarianceRadius; ++i) {
            ivec2 q = p + ivec2(i, j);
            if (!f.inside(q) || f.cur[f.at(q)].sky()) continue;
            float w = (i == 0 && j == 0) ? 1.0f : geometryWeight(sp, f.cur[f.at(q)], vec2(i, j));
            sum += w * vec2(moments[f.at(q)]);
            weights += w;
          }
        mu = sum / weights;
      }
      float var = std::max(0.0f, mu.y - mu.x * mu.x);
      if (!f.moving()) var /= std::max(m.z, 1.0f);
      var = std::min(var, gpu::kSvgfMaxVariance);
      out[f.at(p)] = vec4(vec3(color[f.at(p)]), var);
    }
  return out;
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

// The GGX VNDF sampler the specular pass runs (shaders/shared/vndf.h, compiled here as C++) and the
// split-sum DFG table built from it (render/dfg.h), against analytic densities and quadrature.
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "render/dfg.h"
#include "shaders/shared/vndf.h"

namespace rayster {
namespace {

using gpu::kVndfPi;
constexpr float kPi = kVndfPi;

glm::vec3 viewAt(float thetaV) { return {std::sin(thetaV), 0.0f, std::cos(thetaV)}; }
glm::vec3 reflectAbout(glm::vec3 v, glm::vec3 h) { return 2.0f * glm::dot(v, h) * h - v; }

// Bins of H: x = t/(1+t), t = tan²θ/α² (uniform in x for the plain GGX NDF), times φ.
struct Bins {
  int nx = 12, nphi = 12;
  float alpha;
  float thetaOf(float x) const { return std::atan(alpha * std::sqrt(x / std::max(1.0f - x, 1e-9f))); }
  int index(glm::vec3 h) const {
    float tan2 = (h.x * h.x + h.y * h.y) / std::max(h.z * h.z, 1e-20f);
    float t = tan2 / (alpha * alpha);
    int ix = std::min(int(t / (1.0f + t) * nx), nx - 1);
    float phi = std::atan2(h.y, h.x) + kPi;
    int ip = std::min(int(phi / (2.0f * kPi) * nphi), nphi - 1);
    return ix * nphi + ip;
  }
  // ∫ D_V(h) dω over bin (ix, ip), by midpoint quadrature in θ and φ.
  double probability(glm::vec3 v, int ix, int ip) const {
    const int sub = 24;
    double theta0 = thetaOf(float(ix) / nx), theta1 = ix + 1 == nx ? kPi / 2 : thetaOf(float(ix + 1) / nx);
    double phi0 = 2 * kPi * ip / nphi - kPi, dphi = 2 * kPi / nphi / sub, dtheta = (theta1 - theta0) / sub;
    double sum = 0;
    for (int a = 0; a < sub; ++a)
      for (int b = 0; b < sub; ++b) {
        double th = theta0 + (a + 0.5) * dtheta, ph = phi0 + (b + 0.5) * dphi;
        glm::vec3 h(float(std::sin(th) * std::cos(ph)), float(std::sin(th) * std::sin(ph)), float(std::cos(th)));
        sum += gpu::ggxVndfPdf(v, h, alpha) * std::sin(th) * dtheta * dphi;
      }
    return sum;
  }
};

TEST(Vndf, SampledNormalsFollowTheVisibleNormalDensity) {
  std::mt19937 gen(7);
  std::uniform_real_distribution<float> uni(0.0f, 1.0f);
  for (float alpha : {0.05f, 0.2f, 0.5f, 1.0f})
    for (float thetaV : {0.0f, 0.8f, 1.4f}) {
      const glm::vec3 v = viewAt(thetaV);
      Bins bins{12, 12, alpha};
      const int n = 200000;
      std::vector<int> counts(bins.nx * bins.nphi, 0);
      for (int i = 0; i < n; ++i) ++counts[bins.index(gpu::sampleGgxVndf(v, alpha, {uni(gen), uni(gen)}))];
      double chi2 = 0, total = 0;
      int dof = -1;
      for (int ix = 0; ix < bins.nx; ++ix)
        for (int ip = 0; ip < bins.nphi; ++ip) {
          double p = bins.probability(v, ix, ip);
          total += p;
          double expected = p * n;
          if (expected < 5) continue;
          double d = counts[ix * bins.nphi + ip] - expected;
          chi2 += d * d / expected;
          ++dof;
        }
      EXPECT_NEAR(total, 1.0, 0.01) << "D_V must integrate to 1 (α " << alpha << ", θv " << thetaV << ")";
      // χ² with ~140 degrees of freedom: mean 140, standard deviation ~17; 3× the mean is far out.
      EXPECT_LT(chi2, 3.0 * dof) << "α " << alpha << ", θv " << thetaV << ", dof " << dof;
    }
}

TEST(Vndf, MeanWeightIsAtMostOne) {
  std::mt19937 gen(11);
  std::uniform_real_distribution<float> uni(0.0f, 1.0f);
  for (float roughness : {0.05f, 0.2f, 0.4f, 0.7f, 1.0f})
    for (float nv : {0.05f, 0.3f, 0.7f, 1.0f}) {
      const float alpha = roughness * roughness;
      const glm::vec3 v = viewAt(std::acos(nv));
      double sum = 0, demodulated = 0;
      const int n = 20000;
      const glm::vec2 ab = render::integrateDfg(nv, roughness, 4096);
      for (int i = 0; i < n; ++i) {
        glm::vec3 h = gpu::sampleGgxVndf(v, alpha, {uni(gen), uni(gen)});
        glm::vec3 l = reflectAbout(v, h);
        float w = l.z > 0.0f ? gpu::smithG2OverG1(v.z, l.z, alpha) : 0.0f;
        ASSERT_LE(w, 1.0f + 1e-6f);
        sum += w;
        demodulated += w / (ab.x + ab.y);
      }
      EXPECT_LE(sum / n, 1.0 + 1e-6) << "roughness " << roughness << ", n·v " << nv;
      // Divided by A + B (what the specular pass writes), the mean weight is 1: a lobe average.
      EXPECT_NEAR(demodulated / n, 1.0, 0.02) << "roughness " << roughness << ", n·v " << nv;
    }
}

TEST(Vndf, AlphaZeroIsTheMirrorDirection) {
  std::mt19937 gen(3);
  std::uniform_real_distribution<float> uni(0.0f, 1.0f);
  for (float thetaV : {0.0f, 0.5f, 1.2f, 1.5f}) {
    const glm::vec3 v = viewAt(thetaV), mirror(-v.x, -v.y, v.z);
    for (int i = 0; i < 1000; ++i) {
      glm::vec2 u(uni(gen), uni(gen));
      glm::vec3 h = gpu::sampleGgxVndf(v, 0.0f, u);
      EXPECT_LT(glm::length(h - glm::vec3(0, 0, 1)), 1e-6f);
      EXPECT_LT(glm::length(reflectAbout(v, h) - mirror), 1e-6f);
      EXPECT_FLOAT_EQ(gpu::smithG2OverG1(v.z, mirror.z, 0.0f), 1.0f);
    }
  }
}

// A and B by brute-force quadrature over microfacet normals, independent of the sampler:
// F0·A + B = ∫ F·D·G2·(v·h) / (n·v) dω_h over normals that reflect above the surface.
glm::dvec2 dfgByQuadrature(float nv, float roughness) {
  const float alpha = roughness * roughness;
  const glm::vec3 v = viewAt(std::acos(nv));
  const int nTheta = 2048, nPhi = 256;
  const double dTheta = (kPi / 2) / nTheta, dPhi = 2 * kPi / nPhi;
  glm::dvec2 ab(0.0);
  for (int i = 0; i < nTheta; ++i)
    for (int j = 0; j < nPhi; ++j) {
      double th = (i + 0.5) * dTheta, ph = (j + 0.5) * dPhi;
      glm::vec3 h(float(std::sin(th) * std::cos(ph)), float(std::sin(th) * std::sin(ph)), float(std::cos(th)));
      float vh = glm::dot(v, h);
      if (vh <= 0.0f) continue;
      glm::vec3 l = reflectAbout(v, h);
      if (l.z <= 0.0f) continue;
      double g2 = 1.0 / (1.0 + gpu::smithLambda(nv, alpha) + gpu::smithLambda(l.z, alpha));
      double f = gpu::ggxDistribution(h.z, alpha) * g2 * vh / nv * std::sin(th) * dTheta * dPhi;
      double fc = std::pow(1.0 - vh, 5.0);
      ab += glm::dvec2((1.0 - fc) * f, fc * f);
    }
  return ab;
}

TEST(Dfg, TableMatchesNumericIntegration) {
  const std::vector<glm::vec2> table = render::computeDfgTable();
  const uint32_t n = render::kDfgSize;
  for (uint32_t j : {8u, 16u, 24u, 31u})
    for (uint32_t i : {3u, 15u, 28u, 31u}) {
      const float nv = float(i) / (n - 1), roughness = float(j) / (n - 1);
      glm::dvec2 ref = dfgByQuadrature(nv, roughness);
      glm::vec2 got = table[j * n + i];
      EXPECT_NEAR(got.x, ref.x, 0.01) << "A at n·v " << nv << ", roughness " << roughness;
      EXPECT_NEAR(got.y, ref.y, 0.01) << "B at n·v " << nv << ", roughness " << roughness;
    }
  // Smooth: the lobe is the mirror direction, F0·A + B is Schlick's Fresnel at n·v.
  for (uint32_t i : {1u, 10u, 31u}) {
    const float nv = float(i) / (n - 1), fc = std::pow(1.0f - nv, 5.0f);
    EXPECT_NEAR(table[i].x, 1.0f - fc, 1e-4f);
    EXPECT_NEAR(table[i].y, fc, 1e-4f);
  }
}

}  // namespace
}  // namespace rayster

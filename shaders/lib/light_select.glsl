// Many lights (docs/techniques.md §10): one light per shading point, picked in proportion to its
// importance w = power · cos(max(0, θi − θu)) / d² (θi: angle between the normal and the light's
// centre, θu: the angle the light subtends), and the estimate divided by the probability of the
// pick. With at most kSelectCandidates lights every light is a candidate and the pick is exact
// importance sampling; with more, kSelectCandidates lights drawn uniformly are resampled by
// importance (RIS, Talbot 2005), so the cost stays flat as lights grow and the estimate stays
// unbiased. Needs lib/lights.glsl.
#ifndef RAYSTER_LIGHT_SELECT_GLSL
#define RAYSTER_LIGHT_SELECT_GLSL

const uint kSelectCandidates = 16u;


// Unshadowed importance of light `l` at P with normal N (0 where it cannot contribute).
float lightImportance(LightRecord l, vec3 p, vec3 n) {
  vec3 dir;
  float dist;
  vec3 incident = lightIncident(l, p, dir, dist);
  float power = luminance(incident);
  if (power <= 0.0) return 0.0;
  float sinU = l.type == kLightDirectional ? sin(l.angularRadius) : min(l.radius / max(dist, 1e-6), 1.0);
  float thetaU = asin(sinU);
  float thetaI = acos(clamp(dot(n, dir), -1.0, 1.0));
  return power * max(cos(max(0.0, thetaI - thetaU)), 0.0);
}

// Picks a light for P; returns its index and sets `invPdf` (the estimate's weight), or returns
// frame.lightCount when no light can contribute.
uint selectLight(vec3 p, vec3 n, inout uint rng, out float invPdf) {
  uint count = frame.lightCount;
  bool enumerate = count <= kSelectCandidates;
  uint candidates = enumerate ? count : kSelectCandidates;
  float total = 0.0;  // Σ resampling weights
  uint chosen = count;
  float chosenW = 0.0;
  for (uint k = 0u; k < candidates; ++k) {
    uint i = enumerate ? k : min(uint(rnd(rng) * float(count)), count - 1u);
    float w = lightImportance(loadLight(i), p, n);
    // Resampling weight p̂/q with q = 1/count for uniform candidates; the importance itself when
    // enumerating (then total = Σ w and the pick has probability w / total exactly).
    float r = enumerate ? w : w * float(count);
    if (r <= 0.0) continue;
    total += r;
    if (rnd(rng) * total < r) {  // weighted reservoir: keeps each candidate with probability r / total
      chosen = i;
      chosenW = w;
    }
  }
  if (chosen == count) {
    invPdf = 0.0;
    return count;
  }
  // Exact: 1/p = total / w. RIS: W = (1/p̂(y)) · (1/M) Σ r_j.
  invPdf = enumerate ? total / chosenW : total / (float(candidates) * chosenW);
  return chosen;
}

#endif

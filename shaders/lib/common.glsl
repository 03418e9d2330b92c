// Included by every shader: extensions, shared structs, scene access through device addresses,
// encodings (octahedral normals, sRGB) and random numbers.
#ifndef RAYSTER_COMMON_GLSL
#define RAYSTER_COMMON_GLSL

#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_buffer_reference2 : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_nonuniform_qualifier : require

#include "shared/types.h"
#include "shared/push.h"

const float kPi = 3.14159265358979;

// Rec. 709 luminance of linear RGB.
float luminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

layout(buffer_reference, scalar) readonly buffer Vertices { Vertex v[]; };
layout(buffer_reference, scalar) readonly buffer Indices { uint i[]; };
layout(buffer_reference, scalar) readonly buffer Geometries { GeometryRecord g[]; };
layout(buffer_reference, scalar) readonly buffer Instances { InstanceRecord i[]; };
layout(buffer_reference, scalar) readonly buffer Materials { MaterialRecord m[]; };
layout(buffer_reference, scalar) readonly buffer Lights { LightRecord l[]; };
layout(buffer_reference, scalar) readonly buffer Spheres { SphereRecord s[]; };
layout(buffer_reference, scalar) readonly buffer Positions { vec3 p[]; };  // GeometryRecord::prevPositionAddress
layout(buffer_reference, scalar) readonly buffer VertexColors { uvec2 c[]; };  // RGBA16 UNORM (GeometryRecord)

vec4 unpackVertexColor(uvec2 c) { return vec4(unpackUnorm2x16(c.x), unpackUnorm2x16(c.y)); }

// COLOR_0 of one vertex of a geometry (gpu::GeometryRecord::colorAddress; white without a stream).
vec4 vertexColor(GeometryRecord g, uint vertex) {
  if (g.colorAddress == 0ul) return vec4(1.0);
  return unpackVertexColor(VertexColors(g.colorAddress).c[vertex]);
}
// ... interpolated over triangle `primitive` with barycentric weights w.
vec4 vertexColor(GeometryRecord g, uint primitive, vec3 w) {
  if (g.colorAddress == 0ul) return vec4(1.0);
  Indices idx = Indices(g.indexAddress);
  VertexColors c = VertexColors(g.colorAddress);
  uint base = primitive * 3u;
  return unpackVertexColor(c.c[idx.i[base]]) * w.x + unpackVertexColor(c.c[idx.i[base + 1u]]) * w.y +
         unpackVertexColor(c.c[idx.i[base + 2u]]) * w.z;
}

// Octahedral normal encoding (docs/techniques.md §1).
vec2 octEncode(vec3 n) {
  vec2 p = n.xy / (abs(n.x) + abs(n.y) + abs(n.z));
  return n.z >= 0.0 ? p : (1.0 - abs(p.yx)) * mix(vec2(-1.0), vec2(1.0), greaterThanEqual(p, vec2(0.0)));
}
vec3 octDecode(vec2 e) {
  vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
  float t = max(-n.z, 0.0);
  n.xy += mix(vec2(t), vec2(-t), greaterThanEqual(n.xy, vec2(0.0)));
  return normalize(n);
}

// Exact piecewise sRGB. The G-buffer stores albedo sRGB-encoded in UNORM, by both producers.
vec3 linearToSrgb(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, greaterThan(c, vec3(0.0031308)));
}
vec3 srgbToLinear(vec3 c) {
  return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), greaterThan(c, vec3(0.04045)));
}

// The G-buffer's specular target (RGBA8 UNORM; GBufferValues::specular): rgb the dielectric F0 tint
// t (F0 = F0(η)·t·strength, lib/brdf.glsl), a the strength. t is stored as code/128 up to code 128
// (t = 1, the default, exactly) and 128/(256 − code) above (up to 128, for specular colours that
// raise F0 towards 1), so both halves keep ~1 % steps where tints are used.
vec3 encodeSpecularTint(vec3 t) {
  t = max(t, vec3(0.0));
  vec3 code = mix(round(256.0 - 128.0 / max(t, vec3(1.0))), round(128.0 * t), lessThanEqual(t, vec3(1.0)));
  return clamp(code, 0.0, 255.0) / 255.0;
}
vec3 decodeSpecularTint(vec3 e) {
  vec3 code = round(e * 255.0);
  return mix(128.0 / max(256.0 - code, vec3(1.0)), code / 128.0, lessThanEqual(code, vec3(128.0)));
}
vec4 encodeSpecular(vec4 specular) { return vec4(encodeSpecularTint(specular.rgb), specular.a); }
vec4 decodeSpecular(vec4 texel) { return vec4(decodeSpecularTint(texel.rgb), texel.a); }

// The G-buffer's layers target (RGBA32_UINT; GBufferValues::coat and ::sheen): x the coat normal,
// octahedral in 2 × 16-bit snorm; y the coat factor, coat roughness and sheen roughness, 8 bits
// each; z the sheen colour, sRGB-encoded 8 bits per channel. The last byte of y and z and all of w
// are reserved (0). A pixel without layers (and the background, cleared to 0) has factor and
// colour 0: no coat, no sheen.
uvec4 encodeLayers(vec4 coat, vec4 sheen) {
  return uvec4(packSnorm2x16(coat.xy), packUnorm4x8(vec4(coat.z, coat.w, sheen.a, 0.0)),
               packUnorm4x8(vec4(linearToSrgb(clamp(sheen.rgb, vec3(0.0), vec3(1.0))), 0.0)), 0u);
}
void decodeLayers(uvec4 e, out vec4 coat, out vec4 sheen) {
  vec4 y = unpackUnorm4x8(e.y);
  coat = vec4(unpackSnorm2x16(e.x), y.x, y.y);
  sheen = vec4(srgbToLinear(unpackUnorm4x8(e.z).rgb), y.z);
}

// PCG hash (Jarzynski & Olano 2020); seeds go through the hash (docs/techniques.md §3).
uint pcg(uint v) {
  uint s = v * 747796405u + 2891336453u;
  uint w = ((s >> ((s >> 28u) + 4u)) ^ s) * 277803737u;
  return (w >> 22u) ^ w;
}
uint rngInit(uvec2 px, uint frame, uint seed) { return pcg(px.x + pcg(px.y + pcg(frame ^ pcg(seed)))); }
float rnd(inout uint state) {
  state = pcg(state);
  return float(state >> 8) * (1.0 / 16777216.0);
}

// Streams, so toggling one effect leaves the others' noise unchanged.
const uint kShadowStream = 0x51A0u;
const uint kAlphaStream = 0xA1FAu;
const uint kSpecularStream = 0x5BEC0u;
const uint kGlossyStream = 0x6A055u;  // the first glossy lobe sample only: α = 0 then traces the mirror path's noise
const uint kAoStream = 0xA0A0u;
const uint kIndirectStream = 0x1D1Eu;

// Branchless orthonormal basis (Duff et al. 2017).
void orthonormalBasis(vec3 n, out vec3 t, out vec3 b) {
  float s = n.z >= 0.0 ? 1.0 : -1.0;
  float a = -1.0 / (s + n.z);
  float c = n.x * n.y * a;
  t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
  b = vec3(c, s + n.y * n.y * a, -n.y);
}

// A cosine-weighted direction about n (concentric disk lifted to the hemisphere, Shirley & Chiu):
// with it, the mean of a visibility is its cosine-weighted fraction and π·mean(L) the irradiance.
vec3 cosineSampleHemisphere(vec3 n, vec2 u) {
  vec2 d = 2.0 * u - 1.0;
  vec2 disk = vec2(0.0);
  if (d.x != 0.0 || d.y != 0.0) {
    float r, phi;
    if (abs(d.x) > abs(d.y)) {
      r = d.x;
      phi = (kPi / 4.0) * (d.y / d.x);
    } else {
      r = d.y;
      phi = (kPi / 2.0) - (kPi / 4.0) * (d.x / d.y);
    }
    disk = r * vec2(cos(phi), sin(phi));
  }
  vec3 t, b;
  orthonormalBasis(n, t, b);
  return normalize(t * disk.x + b * disk.y + n * sqrt(max(0.0, 1.0 - dot(disk, disk))));
}

// Depth is reversed (near plane 1, far plane 0): float precision then stays relative at every
// distance, so positions reconstructed from depth are exact enough to start shadow rays from.
const float kBackgroundDepth = 0.0;
bool isBackground(float depth) { return depth <= kBackgroundDepth; }

vec3 worldFromDepth(mat4 worldFromClip, vec2 uv, float depth) {
  vec4 p = worldFromClip * vec4(uv * 2.0 - 1.0, depth, 1.0);
  return p.xyz / p.w;
}

// The camera ray through uv, aimed at the far plane (depth 0) in homogeneous coordinates. Never
// through the near plane: with znear = 1 mm that point is 1 mm from a camera tens of metres from the
// origin, so its float position's rounding (~ulp(|camera|)) tilts the ray by ~1e-3 rad, several
// pixels, and traced hits no longer lie on the ray that depth reconstruction assumes.
vec3 cameraRayDirection(mat4 worldFromClip, vec2 uv, vec3 origin) {
  vec4 p = worldFromClip * vec4(uv * 2.0 - 1.0, 0.0, 1.0);
  return normalize(p.xyz - origin * p.w);
}

// Ray origin for a G-buffer surface: along the geometric normal by more than both the float spacing
// at P and the error of reconstructing P from a quantised depth (one depth ulp moves P by
// ~z²·ulp/near along the view ray: far from the camera that exceeds a fixed epsilon and curved
// surfaces shadow themselves).
float gbufferRayOffset(mat4 worldFromClip, vec2 uv, float depth, vec3 p) {
  float nextDepth = uintBitsToFloat(floatBitsToUint(depth) + 1u);
  float depthError = distance(p, worldFromDepth(worldFromClip, uv, nextDepth));
  return max(max(max(abs(p.x), max(abs(p.y), abs(p.z))), 1.0) * 1e-4, 4.0 * depthError);
}

#endif

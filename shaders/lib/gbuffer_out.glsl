// Fragment outputs of the raster G-buffer producers (triangles and sphere impostors).
layout(location = 0) out vec4 outNormals;
layout(location = 1) out vec4 outAlbedo;
layout(location = 2) out vec4 outMaterial;
layout(location = 3) out vec4 outEmissive;
layout(location = 4) out uint outId;
layout(location = 5) out vec2 outMotion;
layout(location = 6) out vec4 outSpecular;
layout(location = 7) out uvec4 outLayers;

void writeGBuffer(GBufferValues gb, uint id, vec2 motion) {
  outNormals = gb.normals;
  outAlbedo = gb.albedo;
  outMaterial = gb.material;
  outEmissive = gb.emissive;
  outId = id;
  outMotion = motion;
  outSpecular = encodeSpecular(gb.specular);
  outLayers = encodeLayers(gb.coat, gb.sheen);
}

// Per-pixel, per-frame coverage noise for alpha BLEND (stochastic transparency).
float alphaNoise(uvec2 px) { return float(rngInit(px, frame.frameIndex, frame.seed ^ kAlphaStream) >> 8) / 16777216.0; }

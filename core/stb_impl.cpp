// The one stb_image / stb_image_write instance in the program: core/image_io.cpp reads and writes
// images through it and the scene loaders decode glTF/OBJ textures (PNG, JPEG) with it. Other
// decoders stay out: smaller binary, less attack surface for untrusted files.
//
// A translation unit of its own so that the fuzz build (RAYSTER_BUILD_FUZZERS) can leave out one
// UBSan check here only: stb's PNG reader copies zero bytes into a buffer not yet allocated for a
// file whose first IDAT chunk is empty (valid PNG), memcpy(nullptr, p, 0), which UBSan's
// nonnull-attribute check reports though no byte is touched. A real null write would still be
// caught by ASan. Everything else in stb stays checked; stbDecodeHazard() (core/image_io.h) keeps
// out the inputs that do overflow.
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STBI_ONLY_PNG
#define STBI_ONLY_JPEG
#define STBI_ONLY_HDR
#include <stb_image.h>
#include <stb_image_write.h>

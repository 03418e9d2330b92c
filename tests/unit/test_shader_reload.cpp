// Shader hot reload (app/viewer/shader_reload.h): a broken edit reports glslc's error and keeps the
// module; a valid edit installs new SPIR-V that shaders::get returns.
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include <gtest/gtest.h>

#include "app/viewer/shader_reload.h"
#include "shaders/embedded.h"
#include "tests/support/test_dirs.h"

namespace rayster::app {
namespace {
namespace fs = std::filesystem;
using test::readText;

TEST(ViewerShaderReload, ErrorKeepsOldModuleAndValidChangeReplacesIt) {
  const fs::path src = fs::path(RAYSTER_SHADER_DIR);
  const fs::path dir = rayster::test::testDir();
  fs::copy(src, dir, fs::copy_options::recursive);
  const std::string name = "tonemap.comp";
  const fs::path file = dir / (name + ".glsl");
  const std::string original = readText(file);
  const std::vector<uint32_t> embedded(shaders::get(name).begin(), shaders::get(name).end());
  ASSERT_FALSE(embedded.empty());

  ShaderReloader reloader(RAYSTER_GLSLC, dir);
  EXPECT_TRUE(reloader.poll(true).reloaded.empty());  // nothing changed yet

  std::ofstream(file) << original << "\nvoid broken() { this is not glsl }\n";
  fs::last_write_time(file, fs::last_write_time(file) + std::chrono::seconds(2));
  ShaderReloadResult bad = reloader.poll(true);
  EXPECT_TRUE(bad.reloaded.empty());
  EXPECT_NE(bad.error.find("error"), std::string::npos) << bad.error;
  EXPECT_EQ(std::vector<uint32_t>(shaders::get(name).begin(), shaders::get(name).end()), embedded);

  std::ofstream(file) << original << "\nfloat unusedButDifferent(float x) { return x * 3.0; }\n"
                      << "const float kReloadMarker = 42.0;\n";
  fs::last_write_time(file, fs::last_write_time(file) + std::chrono::seconds(4));
  ShaderReloadResult good = reloader.poll(true);
  EXPECT_TRUE(good.error.empty()) << good.error;
  ASSERT_EQ(good.reloaded, std::vector<std::string>{name});
  const std::vector<uint32_t> now(shaders::get(name).begin(), shaders::get(name).end());
  EXPECT_FALSE(now.empty());
  EXPECT_NE(now, embedded);
  shaders::setOverride(name, embedded);  // leave the process's shaders as built
}

// A source with `// variant:` lines reloads its variants too, compiled with their defines: editing
// ao.rgen.glsl in a running viewer also refreshes its raw-rate twin.
TEST(ViewerShaderReload, VariantsAreRecompiledWithTheirSource) {
  // The source tree's own file, only read: compiled from the same path with the build's flags, the
  // SPIR-V (which names its source file, -g) must equal what the build embedded.
  const fs::path dir = fs::path(RAYSTER_SHADER_DIR);
  const fs::path file = dir / "ao.rgen.glsl";
  const std::vector<ShaderVariant> variants = shaderVariants(file);
  ASSERT_EQ(variants.size(), 1u);
  EXPECT_EQ(variants[0].key, "raw_ao.rgen");
  EXPECT_EQ(variants[0].defines, std::vector<std::string>{"RAW_RATE"});

  const std::vector<uint32_t> ao(shaders::get("ao.rgen").begin(), shaders::get("ao.rgen").end());
  const std::vector<uint32_t> raw(shaders::get("raw_ao.rgen").begin(), shaders::get("raw_ao.rgen").end());
  ShaderReloader reloader(RAYSTER_GLSLC, dir);
  ShaderReloadResult r = reloader.compile(file);
  EXPECT_TRUE(r.error.empty()) << r.error;
  EXPECT_EQ(r.reloaded, (std::vector<std::string>{"ao.rgen", "raw_ao.rgen"}));
  // Unchanged sources compile to what the build embedded, each with its own defines.
  EXPECT_EQ(std::vector<uint32_t>(shaders::get("ao.rgen").begin(), shaders::get("ao.rgen").end()), ao);
  EXPECT_EQ(std::vector<uint32_t>(shaders::get("raw_ao.rgen").begin(), shaders::get("raw_ao.rgen").end()), raw);
  EXPECT_NE(ao, raw);
  shaders::setOverride("ao.rgen", ao);
  shaders::setOverride("raw_ao.rgen", raw);
}

}  // namespace
}  // namespace rayster::app

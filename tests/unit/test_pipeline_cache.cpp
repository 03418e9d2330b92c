// The on-disk pipeline cache (rhi/pipeline_cache.h, docs/techniques.md §25): header checks on synthetic
// data, and on the device (lavapipe) a written cache that the next context loads, and damaged or
// foreign files that are ignored without a crash and replaced.
#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "render/passes/denoise.h"
#include "rhi/context.h"
#include "rhi/pipeline_cache.h"
#include "tests/support/test_dirs.h"

namespace rayster::rhi {
namespace {

namespace fs = std::filesystem;

PipelineCacheKey testKey() {
  PipelineCacheKey k;
  k.vendorId = 0x10de;
  k.deviceId = 0x2335;
  for (size_t i = 0; i < k.uuid.size(); ++i) k.uuid[i] = uint8_t(17 * i + 3);
  return k;
}

std::vector<uint8_t> header(const PipelineCacheKey& k, uint32_t headerSize = 32, uint32_t version = 1,
                            size_t payload = 64) {
  std::vector<uint8_t> d(32 + payload, 0xab);
  const uint32_t words[4] = {headerSize, version, k.vendorId, k.deviceId};
  std::memcpy(d.data(), words, 16);
  std::memcpy(d.data() + 16, k.uuid.data(), k.uuid.size());
  return d;
}

TEST(PipelineCacheHeader, AcceptsOnlyThisDevicesVersionOneHeader) {
  const PipelineCacheKey k = testKey();
  EXPECT_TRUE(pipelineCacheUsable(header(k), k));
  EXPECT_TRUE(pipelineCacheUsable(header(k, 32, 1, 0), k));  // a header and nothing else is valid
  PipelineCacheKey other = k;
  other.uuid[7] ^= 1;  // another driver build
  EXPECT_FALSE(pipelineCacheUsable(header(other), k));
  other = k;
  other.deviceId += 1;
  EXPECT_FALSE(pipelineCacheUsable(header(other), k));
  other = k;
  other.vendorId = 0x1002;
  EXPECT_FALSE(pipelineCacheUsable(header(other), k));
  EXPECT_FALSE(pipelineCacheUsable(header(k, 32, 2), k));       // unknown header version
  EXPECT_FALSE(pipelineCacheUsable(header(k, 16), k));          // header too short for the UUID
  EXPECT_FALSE(pipelineCacheUsable(header(k, 4096, 1, 8), k));  // header claims more than the file
  std::vector<uint8_t> truncated = header(k);
  truncated.resize(20);
  EXPECT_FALSE(pipelineCacheUsable(truncated, k));
  EXPECT_FALSE(pipelineCacheUsable({}, k));
}

TEST(PipelineCacheHeader, PathFollowsTheEnvironment) {
  const char* saved = std::getenv("RAYSTER_CACHE_DIR");
  const std::string restore = saved ? saved : "";
  const fs::path chosen = rayster::test::processDir() / "cache-path-test";  // never created
  setenv("RAYSTER_CACHE_DIR", chosen.c_str(), 1);
  const fs::path p = pipelineCachePath(testKey());
  EXPECT_EQ(p.parent_path(), chosen);
  EXPECT_NE(p.filename().string().find("0314253647"), std::string::npos) << p;  // the UUID in hex
  setenv("RAYSTER_CACHE_DIR", "off", 1);
  EXPECT_TRUE(pipelineCachePath(testKey()).empty());
  if (saved)
    setenv("RAYSTER_CACHE_DIR", restore.c_str(), 1);
  else
    unsetenv("RAYSTER_CACHE_DIR");
}

class PipelineCacheDevice : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = rayster::test::testDir() / "cache";  // made by the first save
    const char* saved = std::getenv("RAYSTER_CACHE_DIR");
    hadEnv_ = saved != nullptr;
    if (saved) savedEnv_ = saved;
    setenv("RAYSTER_CACHE_DIR", dir_.c_str(), 1);
  }
  void TearDown() override {
    if (hadEnv_)
      setenv("RAYSTER_CACHE_DIR", savedEnv_.c_str(), 1);
    else
      unsetenv("RAYSTER_CACHE_DIR");
  }
  // A context that builds the denoisers' compute pipelines through the cache, then is destroyed
  // (which writes the cache). Returns the bytes the cache loaded at start-up, or -1 without a device.
  long runOnce(fs::path* file = nullptr) {
    auto created = Context::create({/*validation*/ true, /*requireRayTracing*/ false, ""});
    if (!created) return -1;
    std::unique_ptr<Context> ctx = std::move(created.value());
    EXPECT_NE(ctx->pipelineCache(), VkPipelineCache(VK_NULL_HANDLE));
    const long loaded = long(ctx->pipelineCacheState()->loadedBytes());
    if (file) *file = ctx->pipelineCacheState()->path();
    {
      rhi::PipelineLibrary pipelines(*ctx, VK_NULL_HANDLE);
      for (const char* shader : {"surface.comp", "shadow_temporal.comp", "shadow_atrous.comp", "shadow_atrous_2.comp",
                                 "svgf_temporal.comp", "svgf_atrous.comp", "svgf_atrous_history.comp"})
        pipelines.compute(shader);
    }
    ctx->waitIdle();
    ctx->collectGarbage();
    EXPECT_EQ(ctx->validationErrors(), 0u);
    ctx.reset();
    return loaded;
  }
  static std::vector<uint8_t> read(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }
  fs::path dir_;
  bool hadEnv_ = false;
  std::string savedEnv_;
};

TEST_F(PipelineCacheDevice, SecondRunLoadsWhatTheFirstWrote) {
  fs::path file;
  const long first = runOnce(&file);
  if (first < 0) GTEST_SKIP() << "no Vulkan device";
  EXPECT_EQ(first, 0) << "the folder was empty";
  ASSERT_TRUE(fs::exists(file)) << file;
  const std::vector<uint8_t> written = read(file);
  ASSERT_GE(written.size(), 32u);
  for (const auto& e : fs::directory_iterator(dir_))  // no temporary left behind
    EXPECT_EQ(e.path(), file);
  EXPECT_EQ(runOnce(), long(written.size())) << "the second context starts from the written cache";
}

TEST_F(PipelineCacheDevice, DamagedOrForeignFilesAreIgnoredAndReplaced) {
  fs::path file;
  if (runOnce(&file) < 0) GTEST_SKIP() << "no Vulkan device";
  const std::vector<uint8_t> good = read(file);
  ASSERT_GE(good.size(), 32u);

  std::vector<uint8_t> foreign = good;  // another driver's cache: the UUID differs
  foreign[20] ^= 0xff;
  std::vector<uint8_t> truncated(good.begin(), good.begin() + 24);
  std::vector<uint8_t> garbage(4096);
  for (size_t i = 0; i < garbage.size(); ++i) garbage[i] = uint8_t(i * 131 + 7);
  for (const auto* bad : {&foreign, &truncated, &garbage}) {
    std::ofstream(file, std::ios::binary | std::ios::trunc)
        .write(reinterpret_cast<const char*>(bad->data()), std::streamsize(bad->size()));
    EXPECT_EQ(runOnce(), 0) << "a bad file must not reach the driver";
    const std::vector<uint8_t> after = read(file);
    ASSERT_GE(after.size(), 32u);
    EXPECT_TRUE(std::equal(after.begin(), after.begin() + 32, good.begin())) << "replaced by a valid cache";
  }
}

}  // namespace
}  // namespace rayster::rhi

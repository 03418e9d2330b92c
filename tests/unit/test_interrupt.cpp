// The pieces of a stopped or failing render (core/interrupt.h, app/fault_injection.h); the
// processes themselves are tests/render/test_sequence_faults.cpp.
#include <signal.h>

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "app/fault_injection.h"
#include "core/interrupt.h"
#include "tests/support/test_dirs.h"

namespace rayster::test {
namespace {

namespace fs = std::filesystem;

TEST(Interrupt, TrackedTemporaryFilesAreRemovedAndReleasedOnesKept) {
  const fs::path dir = testDir();
  const fs::path kept = dir / "kept.tmp-1", removed = dir / "removed.tmp-1";
  std::ofstream(kept) << "x";
  std::ofstream(removed) << "x";
  { const TempFileInProgress released(kept); }
  const TempFileInProgress tracked(removed);
  EXPECT_EQ(removeTempFilesInProgress(), 1);
  EXPECT_TRUE(fs::exists(kept));
  EXPECT_FALSE(fs::exists(removed));
  EXPECT_EQ(removeTempFilesInProgress(), 0) << "already gone";
}

TEST(Interrupt, ExitCodesAre128PlusTheSignal) {
  EXPECT_EQ(int(interruptExitCode(SIGINT)), 130);
  EXPECT_EQ(int(interruptExitCode(SIGTERM)), 143);
  const Error e = interruptedError(SIGTERM, "3 of 6 frames written");
  EXPECT_EQ(e.code, kExitTerminated);
  EXPECT_EQ(e.message, "interrupted by SIGTERM: 3 of 6 frames written");
}

TEST(Interrupt, InjectedFailuresParseAndBadOnesAreRefused) {
  auto lost = app::parseInjectedFailure("lost:3");
  ASSERT_TRUE(lost.ok() && lost->has_value());
  EXPECT_EQ((*lost)->result, VK_ERROR_DEVICE_LOST);
  EXPECT_EQ((*lost)->frame, 3);
  auto oom = app::parseInjectedFailure("oom:0");
  ASSERT_TRUE(oom.ok() && oom->has_value());
  EXPECT_EQ((*oom)->result, VK_ERROR_OUT_OF_DEVICE_MEMORY);
  auto none = app::parseInjectedFailure(nullptr);
  ASSERT_TRUE(none.ok());
  EXPECT_FALSE(none->has_value());
  for (const char* bad : {"lost", "lost:", "lost:-1", "gone:3", "lost:3x", "oom:3:4"}) {
    auto r = app::parseInjectedFailure(bad);
    ASSERT_FALSE(r.ok()) << bad;
    EXPECT_EQ(r.error().code, ExitCode::BadArguments) << bad;
  }
}

}  // namespace
}  // namespace rayster::test

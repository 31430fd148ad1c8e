// Static files stay inside their folder (http/static_files.h).
#include <gtest/gtest.h>

#include <sys/stat.h>

#include "http/static_files.h"
#include "test_support.h"

namespace rockbake::http {
namespace {

namespace fs = std::filesystem;

TEST(StaticFiles, OnlyRegularFilesInsideTheRoot) {
  test::TempDir dir;
  const fs::path root = dir.path() / "www";
  fs::create_directories(root / "js");
  test::writeText(root / "index.html", "<p>page</p>");
  test::writeText(root / "js" / "main.js", "export {};");
  test::writeText(dir.path() / "secret.txt", "secret");
  fs::create_symlink(dir.path() / "secret.txt", root / "leak.txt");
  fs::create_symlink(root / "index.html", root / "alias.html");
  ASSERT_EQ(::mkfifo((root / "fifo.js").c_str(), 0600), 0);

  const auto response = fileResponse(root, "js/main.js");
  ASSERT_TRUE(response);
  EXPECT_EQ(response->body, "export {};");
  EXPECT_EQ(response->content_type, "text/javascript; charset=utf-8");
  EXPECT_TRUE(fileUnder(root, "alias.html")) << "a link that stays inside is followed";
  for (const char* path : {"../secret.txt", "js/../../secret.txt", "/etc/passwd", "leak.txt", "js", ".", "",
                           "js\\main.js", "fifo.js", "missing.js", "./index.html"})
    EXPECT_FALSE(fileResponse(root, path)) << path;
  EXPECT_FALSE(fileUnder(root, std::string("index.html\0.js", 14)));
}

}  // namespace
}  // namespace rockbake::http

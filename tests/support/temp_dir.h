#pragma once
/// \file temp_dir.h
/// \brief A folder under the system temp dir, removed with everything in it at the end of a
/// test (for tests that write input files).

#include <filesystem>
#include <string>
#include <string_view>

namespace osd_cull::test {

/// \brief A fresh folder <temp>/<prefix><pid>_<n>; removed by the destructor.
class TempDir {
 public:
  explicit TempDir(std::string_view prefix);
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  /// \brief Writes `bytes` as is to the file `name` in the folder and returns its path.
  std::filesystem::path write(const std::string& name, const std::string& bytes) const;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace osd_cull::test

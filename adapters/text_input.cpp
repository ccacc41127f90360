#include "adapters/text_input.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <system_error>

namespace osd_cull::adapters::detail {

std::string readFileBytes(const std::filesystem::path& path) {
  const std::string name = path.string();
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) throw Error(name + ": file not found");
  if (std::filesystem::is_directory(status))
    throw Error(name + ": is a directory, not a mesh file");
  // Devices and pipes may never end (/dev/zero): only regular files are read.
  if (!std::filesystem::is_regular_file(status)) throw Error(name + ": is not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(name + ": cannot open the file for reading");
  std::string bytes;
  char buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0)
    bytes.append(buffer, static_cast<size_t>(in.gcount()));
  if (in.bad()) throw Error(name + ": read error");
  return bytes;
}

std::string lowerExtension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

void fail(const std::string& file, int line, const std::string& problem) {
  if (line > 0) throw Error(file + ":" + std::to_string(line) + ": " + problem);
  throw Error(file + ": " + problem);
}

LineReader::LineReader(std::string_view text, std::string file, bool joinContinuations)
    : text_(text), file_(std::move(file)), joinContinuations_(joinContinuations) {}

std::string_view LineReader::takePhysicalLine() {
  const size_t end = text_.find('\n', pos_);
  std::string_view raw = text_.substr(pos_, end == std::string_view::npos ? end : end - pos_);
  pos_ = end == std::string_view::npos ? text_.size() : end + 1;
  if (!raw.empty() && raw.back() == '\r') raw.remove_suffix(1);
  for (unsigned char c : raw) {
    // Text formats never contain these; a file that does is binary or corrupt.
    if (c < 0x20 && c != '\t' && c != '\r' && c != '\f' && c != '\v') {
      lineNumber_ = nextLine_;
      char hex[8];
      std::snprintf(hex, sizeof hex, "0x%02x", c);
      fail(std::string("binary data (byte ") + hex +
           ") in a text file; the file is corrupt or not in this format");
    }
  }
  ++nextLine_;
  return raw;
}

bool LineReader::next() {
  if (pos_ >= text_.size()) return false;
  lineNumber_ = nextLine_;
  line_ = takePhysicalLine();
  if (!joinContinuations_ || line_.empty() || line_.back() != '\\') return true;
  joined_.assign(line_.substr(0, line_.size() - 1));
  while (pos_ < text_.size()) {
    std::string_view more = takePhysicalLine();
    const bool continues = !more.empty() && more.back() == '\\';
    if (continues) more.remove_suffix(1);
    joined_ += ' ';
    joined_.append(more);
    if (!continues) break;
  }
  line_ = joined_;
  return true;
}

size_t LineReader::remainingLines() const {
  if (pos_ >= text_.size()) return 0;
  const std::string_view rest = text_.substr(pos_);
  return static_cast<size_t>(std::count(rest.begin(), rest.end(), '\n')) +
         (rest.back() == '\n' ? 0 : 1);
}

void LineReader::fail(const std::string& problem) const {
  detail::fail(file_, lineNumber_, problem);
}

std::vector<std::string_view> splitTokens(std::string_view text) {
  std::vector<std::string_view> tokens;
  auto isSpace = [](char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
  };
  size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && isSpace(text[i])) ++i;
    const size_t start = i;
    while (i < text.size() && !isSpace(text[i])) ++i;
    if (i > start) tokens.push_back(text.substr(start, i - start));
  }
  return tokens;
}

std::optional<double> parseDouble(std::string_view token) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty() || token.front() == '+') return std::nullopt;
  double value = 0.0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  // Out-of-range magnitudes (1e999) are reported as result_out_of_range: treat them as Inf
  // so the caller's finiteness check names them.
  if (ec == std::errc::result_out_of_range && end == token.data() + token.size())
    return token.front() == '-' ? -HUGE_VAL : HUGE_VAL;
  if (ec != std::errc() || end != token.data() + token.size()) return std::nullopt;
  return value;
}

std::optional<int64_t> parseInt(std::string_view token) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty() || token.front() == '+') return std::nullopt;
  int64_t value = 0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || end != token.data() + token.size()) return std::nullopt;
  return value;
}

std::string quote(std::string_view token) {
  constexpr size_t kMax = 40;
  std::string out = "'";
  for (size_t i = 0; i < token.size() && i < kMax; ++i) {
    const unsigned char c = static_cast<unsigned char>(token[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
    } else {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", c);
      out += hex;
    }
  }
  if (token.size() > kMax) out += "...";
  return out + "'";
}

}  // namespace osd_cull::adapters::detail

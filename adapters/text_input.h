#pragma once
/// \file text_input.h
/// \brief Internal helpers shared by the text-format readers: reading a whole file, walking
/// its lines with line numbers, strict number parsing, and errors of the form
/// "FILE:LINE: problem".

#include "osd_cull/error.h"

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace osd_cull::adapters::detail {

/// \brief The whole file as bytes. \throws Error naming the file when it is missing, is a
/// directory, or cannot be read.
std::string readFileBytes(const std::filesystem::path& path);

/// \brief The file's extension in lower case, with the dot (".obj"); empty if it has none.
std::string lowerExtension(const std::filesystem::path& path);

/// \brief Throws Error "FILE:LINE: problem" (or "FILE: problem" when line <= 0).
[[noreturn]] void fail(const std::string& file, int line, const std::string& problem);

/// \brief Walks the logical lines of a text: accepts LF and CRLF line ends, optionally joins
/// lines ending in a backslash, and rejects bytes that never occur in a text file (NUL and
/// other control characters), so binary garbage is an error rather than a silent skip.
class LineReader {
 public:
  LineReader(std::string_view text, std::string file, bool joinContinuations);

  /// \brief Advances to the next logical line; false at the end of the text.
  bool next();
  /// \brief The current logical line without its line end.
  std::string_view line() const { return line_; }
  /// \brief 1-based number of the first physical line of the current logical line.
  int lineNumber() const { return lineNumber_; }
  /// \brief Physical lines not yet read (an upper bound on records still to come).
  size_t remainingLines() const;
  const std::string& file() const { return file_; }

  /// \brief Throws Error "FILE:LINE: problem" for the current line.
  [[noreturn]] void fail(const std::string& problem) const;

 private:
  std::string_view takePhysicalLine();

  std::string_view text_;
  std::string file_;
  bool joinContinuations_;
  size_t pos_ = 0;
  int nextLine_ = 1;
  int lineNumber_ = 0;
  std::string joined_;
  std::string_view line_;
};

/// \brief Splits at spaces and tabs (and stray '\r', '\f', '\v').
std::vector<std::string_view> splitTokens(std::string_view text);

/// \brief Parses a whole token as a decimal floating-point number (a leading '+' is
/// accepted). "nan" and "inf" parse (the caller decides whether they are allowed).
std::optional<double> parseDouble(std::string_view token);

/// \brief Parses a whole token as a decimal integer (a leading '+' is accepted).
std::optional<int64_t> parseInt(std::string_view token);

/// \brief The token quoted for an error message, shortened if long and with
/// non-printable bytes escaped.
std::string quote(std::string_view token);

}  // namespace osd_cull::adapters::detail

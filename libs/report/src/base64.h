// Base64 (RFC 4648, with padding) of bytes, for what the report embeds in
// its page and its viewer's data script. Internal to meshnbv::report.
#pragma once

#include <cstddef>
#include <string>

namespace meshnbv::report_detail {

inline std::string base64(const void* data, std::size_t size) {
  static const char* chars = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const auto* bytes = static_cast<const unsigned char*>(data);
  std::string out;
  out.reserve((size + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < size; i += 3) {
    const unsigned v = unsigned(bytes[i]) << 16 | unsigned(bytes[i + 1]) << 8 | unsigned(bytes[i + 2]);
    out += chars[v >> 18 & 63];
    out += chars[v >> 12 & 63];
    out += chars[v >> 6 & 63];
    out += chars[v & 63];
  }
  if (i < size) {
    unsigned v = unsigned(bytes[i]) << 16;
    if (i + 1 < size) v |= unsigned(bytes[i + 1]) << 8;
    out += chars[v >> 18 & 63];
    out += chars[v >> 12 & 63];
    out += i + 1 < size ? chars[v >> 6 & 63] : '=';
    out += '=';
  }
  return out;
}

inline std::string base64(const std::string& bytes) { return base64(bytes.data(), bytes.size()); }

}  // namespace meshnbv::report_detail

// EXIF of a photo through exiv2 (Debian libexiv2-dev): GPS position and
// focal length, what georeferencing a scene from its photos needs
// (meshnbv::mission, docs/missions.md). Tags that are absent stay empty;
// tags that are present but malformed (zero denominators, latitude beyond
// 90 degrees, a reference other than N/S/E/W) are an Error naming the file.
#pragma once

#include <optional>
#include <string>

namespace meshnbv::io {

struct ExifInfo {
  // WGS84 degrees (south and west negative); metres above sea level
  // (GPSAltitudeRef 1 = below: negative).
  std::optional<double> latitude, longitude, altitude;
  std::optional<double> focal_length_mm;    // Exif.Photo.FocalLength
  std::optional<double> focal_length_35mm;  // Exif.Photo.FocalLengthIn35mmFilm
  bool has_gps() const { return latitude && longitude; }
};

// Throws Error when the file is missing or not an image exiv2 reads. Only
// the metadata is read (exiv2 opens the file itself), not the pixels.
ExifInfo read_exif(const std::string& path);
// The same, but nullopt for a file of a type exiv2 does not know (PGM, PPM,
// ...: no EXIF to hold); still an Error for a missing file or bad tags.
std::optional<ExifInfo> read_exif_if_known_type(const std::string& path);
// The same from the bytes of a file (`name` for messages); for the fuzzer.
ExifInfo read_exif_from_memory(const std::string& bytes, const std::string& name);

// What a photo's header says, without decoding its pixels (`meshnbv info`).
struct PhotoHeader {
  int width = 0, height = 0;  // as stored
  int bits = 0;               // per channel: PNG's IHDR, TIFF's BitsPerSample, 8 for JPEG; 0 unknown
  int orientation = 0;  // the EXIF orientation tag, 1..8; 0 absent (or outside 1..8, which decoders ignore)
};
// Throws Error when the file is missing or not an image exiv2 reads;
// nullopt for a file of a type exiv2 does not know.
std::optional<PhotoHeader> read_photo_header(const std::string& path);
// The same from the bytes of a file (`name` for messages); for the fuzzer.
std::optional<PhotoHeader> read_photo_header_from_memory(const std::string& bytes, const std::string& name);

}  // namespace meshnbv::io

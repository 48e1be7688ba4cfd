// Helpers shared by the JSON structure-from-motion readers (OpenMVG
// sfm_data.json, AliceVision sfm.json / cameras.sfm). Internal to meshnbv::io.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "meshnbv/camera.h"

namespace meshnbv::io::sfm_json {

using nlohmann::json;

// The document, or Error("malformed JSON: ...").
json parse(const std::string& path);
// A member that must be present; Error naming `key` and `where` otherwise.
const json& member(const json& j, const char* key, const std::string& file, const std::string& where);
// A number written as a number or as a string of one (AliceVision writes strings).
double number(const json& j, const std::string& file, const std::string& where);
long long integer(const json& j, const std::string& file, const std::string& where);
// An array of exactly `n` numbers (n = 0: any length).
std::vector<double> numbers(const json& j, std::size_t n, const std::string& file,
                            const std::string& where);
int image_size(const json& j, const std::string& file, const std::string& where);
// Text of a string or number member.
std::string text(const json& j, const std::string& file, const std::string& where);

// Brown lens of OpenMVG and AliceVision ("t1", "t2" are OpenCV's p1, p2):
// x_d = x (1 + k1 r^2 + k2 r^4 + k3 r^6) + t2 (r^2 + 2 x^2) + 2 t1 x y.
void set_brown(const std::vector<double>& k1k2k3t1t2, PinholeCamera* c);

}  // namespace meshnbv::io::sfm_json

// Measured BRDFs in the MERL binary format.
#include "prt/brdf/merl.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>

#include "prt/brdf/lambert.h"
#include "sh/constants.h"

namespace prt::brdf {

namespace {

using sh::kPi;
constexpr std::size_t kCells = std::size_t{kMerlThetaH} * kMerlThetaD * kMerlPhiD;

Vec3 rotate_z(const Vec3& v, double a) {
  const double c = std::cos(a), s = std::sin(a);
  return {c * v.x - s * v.y, s * v.x + c * v.y, v.z};
}

Vec3 rotate_y(const Vec3& v, double a) {
  const double c = std::cos(a), s = std::sin(a);
  return {c * v.x + s * v.z, v.y, -s * v.x + c * v.z};
}

int clamp_index(double x, int n) {
  if (!(x > 0.0)) return 0;
  return std::min(static_cast<int>(x), n - 1);
}

Status file_error(const std::string& path, const std::string& what) {
  return Status::Error(path + ": " + what);
}

}  // namespace

HalfDiffAngles half_diff_angles(const Vec3& wi, const Vec3& wo) {
  const Vec3 h = normalize(wi + wo);
  HalfDiffAngles a;
  a.theta_h = std::acos(std::clamp(h.z, -1.0, 1.0));
  const double phi_h = std::atan2(h.y, h.x);
  const Vec3 d = rotate_y(rotate_z(wi, -phi_h), -a.theta_h);
  a.theta_d = std::acos(std::clamp(d.z, -1.0, 1.0));
  a.phi_d = std::atan2(d.y, d.x);
  return a;
}

Result<MerlBrdf> MerlBrdf::read(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return file_error(path, "cannot open MERL BRDF file");
  // The size first, so that nothing is allocated for a file of the wrong size.
  const std::streamoff end = in.tellg();
  if (end < 0 || !in.seekg(0)) return file_error(path, "cannot read MERL BRDF file");
  const auto size = static_cast<std::size_t>(end);
  if (size < 12) {
    return file_error(
        path, "truncated MERL file: " + std::to_string(size) + " bytes, the header alone needs 12");
  }
  int32_t dims[3];
  if (!in.read(reinterpret_cast<char*>(dims), 12))
    return file_error(path, "cannot read MERL BRDF file");
  if (dims[0] != kMerlThetaH || dims[1] != kMerlThetaD || dims[2] != kMerlPhiD) {
    return file_error(path, "MERL dimensions are " + std::to_string(dims[0]) + "x" +
                                std::to_string(dims[1]) + "x" + std::to_string(dims[2]) +
                                ", expected 90x90x180");
  }
  const std::size_t want = 12 + 3 * kCells * sizeof(double);
  if (size != want) {
    return file_error(path, std::string(size < want ? "truncated" : "oversized") + " MERL file: " +
                                std::to_string(size) + " bytes, expected " + std::to_string(want));
  }
  std::vector<double> table(3 * kCells);
  if (!in.read(reinterpret_cast<char*>(table.data()),
               static_cast<std::streamsize>(table.size() * sizeof(double))))
    return file_error(path, "cannot read MERL BRDF file");
  for (std::size_t i = 0; i < table.size(); ++i) {
    if (!std::isfinite(table[i])) {
      return file_error(path, "non-finite MERL value at index " + std::to_string(i));
    }
    table[i] = std::max(0.0, table[i]) * kMerlScale[i / kCells];
  }
  return MerlBrdf(std::move(table));
}

Rgb MerlBrdf::eval(const Vec3& wi, const Vec3& wo) const {
  if (wi.z <= 0.0 || wo.z <= 0.0) return {};
  const HalfDiffAngles a = half_diff_angles(wi, wo);
  const double phi_d = a.phi_d < 0.0 ? a.phi_d + kPi : a.phi_d;
  const int ih = clamp_index(std::sqrt(a.theta_h / (kPi / 2)) * kMerlThetaH, kMerlThetaH);
  const int id = clamp_index(a.theta_d / (kPi / 2) * kMerlThetaD, kMerlThetaD);
  const int ip = clamp_index(phi_d / kPi * kMerlPhiD, kMerlPhiD);
  const std::size_t i =
      (std::size_t{static_cast<unsigned>(ih)} * kMerlThetaD + id) * kMerlPhiD + ip;
  return {table_[i], table_[kCells + i], table_[2 * kCells + i]};
}

BrdfSample MerlBrdf::sample(const Vec3& wo, double u1, double u2) const {
  return sample_by_cosine(*this, wo, u1, u2);
}

double MerlBrdf::pdf(const Vec3& wo, const Vec3& wi) const {
  return cosine_sampling_pdf(wo, wi);
}

}  // namespace prt::brdf

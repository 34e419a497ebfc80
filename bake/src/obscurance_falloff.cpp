// bake/src/obscurance_falloff.cpp — the falloffs of obscurance (obscurance_falloff.h).
#include "bake/obscurance_falloff.h"

#include <cmath>

namespace prt::bake {

double obscurance_weight(ObscuranceFalloff falloff, double d, double D) {
  if (!(d < D)) return 1.0;  // beyond the obscurance distance, or no hit (d = ∞)
  const double t = d > 0.0 ? d / D : 0.0;
  switch (falloff) {
    case ObscuranceFalloff::Linear:
      return t;
    case ObscuranceFalloff::Exponential:
      return -std::expm1(-4.0 * t) / -std::expm1(-4.0);
    case ObscuranceFalloff::Smoothstep:
      return t * t * (3.0 - 2.0 * t);
    case ObscuranceFalloff::Constant:
      return 0.0;
  }
  return 0.0;
}

const char* obscurance_falloff_name(ObscuranceFalloff falloff) {
  switch (falloff) {
    case ObscuranceFalloff::Linear:
      return "linear";
    case ObscuranceFalloff::Exponential:
      return "exponential";
    case ObscuranceFalloff::Smoothstep:
      return "smoothstep";
    case ObscuranceFalloff::Constant:
      return "constant";
  }
  return "linear";
}

std::optional<ObscuranceFalloff> parse_obscurance_falloff(const std::string& text) {
  for (const ObscuranceFalloff f : {ObscuranceFalloff::Linear, ObscuranceFalloff::Exponential,
                                    ObscuranceFalloff::Smoothstep, ObscuranceFalloff::Constant})
    if (text == obscurance_falloff_name(f)) return f;
  return std::nullopt;
}

}  // namespace prt::bake

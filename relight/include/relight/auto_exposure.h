// relight/auto_exposure.h — THE exposure rule: the exposure every command that tone-maps (prt
// relight of every file kind, prt radiosity, prt demo) chooses when none is given.
//
// Rule: the median Rec. 709 luminance Y = 0.2126 R + 0.7152 G + 0.0722 B of the vertices' exit
// radiance (linear, 3 floats per vertex) is brought to kAutoExposureKey before the filmic curve
// of relight/tone_map.h: EV = log2(key / median), rounded to the nearest 1/4 EV. A key of 0.3
// becomes about 0.69 after the ACES fit and the sRGB OETF: the typical surface sits a little
// above mid grey and highlights up to about 36 times brighter (5.2 EV) roll off before white.
// Vertices whose luminance is NaN, infinite or ≤ 0 (SH ringing, unlit) are left out of the
// median; when none is left the exposure is 0 EV. The median is over vertices, not pixels, so
// the choice does not depend on the camera, the image size or the background.
#pragma once

#include <string>
#include <vector>

namespace prt::relight {

// The display-referred key: the linear value the median vertex luminance is exposed to.
constexpr double kAutoExposureKey = 0.3;

// Exposure in EV (a multiple of 0.25) for radiance_rgb (3 floats per vertex); see above.
float choose_auto_exposure(const std::vector<float>& radiance_rgb);

// For the user: "exposure +1.50 EV (automatic: …)" or "exposure +1.50 EV (--exposure)".
std::string describe_exposure(float exposure_ev, bool automatic);

}  // namespace prt::relight

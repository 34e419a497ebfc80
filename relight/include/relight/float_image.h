// relight/float_image.h — the decoded image of scene/float_image.h under relight's names (the
// image decoding the scene loader needs for textures lives in scene/, below relight).
#pragma once

#include "scene/float_image.h"

namespace prt::relight {

using scene::FloatImage;
using scene::kMaxImageTexels;

}  // namespace prt::relight

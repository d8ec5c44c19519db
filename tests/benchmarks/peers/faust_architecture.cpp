#pragma once
// The smallest Faust architecture: the generated dsp class and what it derives from, with
// double samples in and out, for the peer benchmark to drive directly.
#define FAUSTFLOAT double
#include <algorithm>
#include <cmath>
#include <cstdint>

#include <faust/dsp/dsp.h>
#include <faust/gui/UI.h>
#include <faust/gui/meta.h>

<< includeIntrinsic >>

    << includeclass >>

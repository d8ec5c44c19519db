#pragma once
// A bowed chain of any size, for benchmarks and scaling tests: N equal masses between fixed
// ends, half the stability bound per link, the standard bow module near one end.

#include "archet/model/model.hpp"

namespace archet {

Model build_bowed_chain(int masses);

}  // namespace archet

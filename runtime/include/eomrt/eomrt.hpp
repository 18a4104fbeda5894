#pragma once
/// \file
/// Umbrella header of the eomrt runtime: include this to get every runtime algorithm.
#include "eomrt/tableau.hpp"
#include "eomrt/rk_fixed.hpp"

// A dp/ header that includes a room above dp: the test layering_sees_back_include runs the
// include check over this directory and expects it to name this line.
#pragma once
#include "output/frontier_cache.hpp"
#include "physics/train.hpp"

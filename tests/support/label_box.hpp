#pragma once
// The bounding box of one object's pixels in a YCB-Video label image: the library's reader (eval/label_box.hpp),
// which `depthtrack eval` starts its box cases from.
#include "eval/label_box.hpp"

namespace depthtrack::test {

using depthtrack::label_box;

}  // namespace depthtrack::test

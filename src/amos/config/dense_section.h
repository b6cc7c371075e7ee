#pragma once
// The `Dense.*` keys: the dense static map of `run --dense` (dense/dense_options.h, docs/dense.md).
#include "amos/config/key_list.h"
#include "amos/dense/dense_options.h"

namespace amos::config {

KeySection denseKeys(dense::DenseOptions& o);

}  // namespace amos::config

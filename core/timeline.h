#pragma once
// The time axis lives in foundation/ (the scene parser checks pulse widths with it too); this
// header stays so that the render code's includes need not change.
#include "foundation/timeline.h"

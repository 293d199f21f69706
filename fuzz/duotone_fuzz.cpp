#include "fuzz_main.h"
#include "fuzz_targets.h"

MEANDER_FUZZ_ENTRY(meander::fuzz::duotone_target(bytes))

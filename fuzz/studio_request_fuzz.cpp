#include "fuzz_main.h"
#include "fuzz_targets.h"

MEANDER_FUZZ_ENTRY(meander::fuzz::make_request_target(bytes))

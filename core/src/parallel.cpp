#include "core/parallel.h"

#include <tbb/info.h>

namespace penumbra {

int thread_count(const Context& ctx) {
    return ctx.threads > 0 ? ctx.threads : tbb::info::default_concurrency();
}

} // namespace penumbra

#include "core/context.h"

#include <algorithm>

namespace penumbra {

ProgressStage::ProgressStage(const Context& ctx, std::string_view stage)
    : sink_(ctx.progress.get()) {
    if (sink_)
        sink_->begin(stage);
}

ProgressStage::~ProgressStage() {
    if (sink_)
        sink_->end();
}

void ProgressStage::update(double fraction) {
    if (sink_ && !sink_->update(std::clamp(fraction, 0.0, 1.0)))
        throw Cancelled();
}

} // namespace penumbra

#include "core/rng.h"

namespace penumbra {

void Pcg32::advance(std::int64_t delta_signed) {
    // Brown, "Random number generation with arbitrary strides", 1994: compose the LCG step
    // with itself by squaring.
    std::uint64_t cur_mult = k_mult, cur_plus = inc_, acc_mult = 1u, acc_plus = 0u;
    auto delta = std::uint64_t(delta_signed);
    while (delta > 0) {
        if (delta & 1) {
            acc_mult *= cur_mult;
            acc_plus = acc_plus * cur_mult + cur_plus;
        }
        cur_plus = (cur_mult + 1) * cur_plus;
        cur_mult *= cur_mult;
        delta /= 2;
    }
    state_ = acc_mult * state_ + acc_plus;
}

} // namespace penumbra

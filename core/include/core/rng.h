#pragma once
// PCG32 (O'Neill 2014) and a 64-bit mixing hash. Every random decision draws from a stream
// named by content (purpose, ids, seed), never by thread or time, so results do not depend on
// the thread count or the scheduling.

#include <cstdint>
#include <initializer_list>

namespace penumbra {

/// Purpose tags of random streams; append only, so that existing streams never shift.
enum class RngPurpose : std::uint64_t {
    form_factor_visibility = 1,
    form_factor_quadrature = 2,
    escape_estimate = 3,
    point_light_visibility = 4,
    sensor_visibility = 5,
    pixel_sample = 6,
    vertex_visibility = 7,
    cluster_visibility = 8,
    sun_visibility = 9,
    exact_visibility = 10,
    sky_visibility = 11,
    texel_visibility = 12, ///< lightmap texel samples (issue #29)
    probe_directions = 13, ///< light probes' gather rays (issue #29)
    texel_gather = 14,     ///< directional lightmaps' gather rays (issue #29)
    caustic_photon = 15,   ///< caustic photons of the final gather (issue #28)
    texel_paths = 16,      ///< `penumbra lightmap --gather`: final-gather paths (issue #29)
    gather_split = 17,     ///< the render's split light and gather samples (issue #28)
    /// The irradiance cache's records (issue #28).
    irradiance_record = 18,
};

/// SplitMix64 finaliser: a strong 64-bit mix.
constexpr std::uint64_t mix64(std::uint64_t x) {
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ULL;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebULL;
    x ^= x >> 31;
    return x;
}

/// Hash of a sequence of 64-bit words (order matters).
constexpr std::uint64_t hash_words(std::initializer_list<std::uint64_t> words) {
    std::uint64_t h = 0x9e3779b97f4a7c15ULL;
    for (std::uint64_t w : words)
        h = mix64(h ^ mix64(w + 0x632be59bd9b4e019ULL));
    return h;
}

class Pcg32 {
public:
    Pcg32() { seed(0x853c49e6748fea9bULL, 0xda3e39cb94b95bdbULL); }
    Pcg32(std::uint64_t state_seed, std::uint64_t stream) { seed(state_seed, stream); }

    /// A stream named by content: purpose, up to three ids and the master seed.
    static Pcg32 for_stream(RngPurpose purpose, std::uint64_t a, std::uint64_t b, std::uint64_t c,
                            std::uint64_t master_seed) {
        std::uint64_t h = hash_words({std::uint64_t(purpose), a, b, c, master_seed});
        return Pcg32(h, mix64(h ^ 0x2545f4914f6cdd1dULL));
    }

    void seed(std::uint64_t state_seed, std::uint64_t stream) {
        state_ = 0;
        inc_ = (stream << 1u) | 1u;
        next_u32();
        state_ += state_seed;
        next_u32();
    }

    std::uint32_t next_u32() {
        std::uint64_t old = state_;
        state_ = old * k_mult + inc_;
        auto xorshifted = std::uint32_t(((old >> 18u) ^ old) >> 27u);
        auto rot = std::uint32_t(old >> 59u);
        return (xorshifted >> rot) | (xorshifted << ((~rot + 1u) & 31));
    }

    /// Uniform float in [0, 1).
    float next_float() { return float(next_u32() >> 8) * 0x1p-24f; }
    /// Uniform double in [0, 1).
    double next_double() { return double(next_u32()) * 0x1p-32; }

    /// Skip ahead by \p delta draws in O(log delta) (Brown 1994).
    void advance(std::int64_t delta);

    std::uint64_t state() const { return state_; }

private:
    static constexpr std::uint64_t k_mult = 0x5851f42d4c957f2dULL;
    std::uint64_t state_ = 0, inc_ = 0;
};

} // namespace penumbra

#pragma once
// Small fixed-size vector math. Geometry is double precision (metres); per-element arrays
// handed to Embree use Vec3f.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

namespace penumbra {

template <typename T> struct Vec3T {
    T x = 0, y = 0, z = 0;

    constexpr Vec3T() = default;
    constexpr Vec3T(T x_, T y_, T z_) : x(x_), y(y_), z(z_) {}
    template <typename U>
    constexpr explicit Vec3T(const Vec3T<U>& o) : x(T(o.x)), y(T(o.y)), z(T(o.z)) {}

    constexpr T operator[](std::size_t i) const { return i == 0 ? x : (i == 1 ? y : z); }
    constexpr T& operator[](std::size_t i) { return i == 0 ? x : (i == 1 ? y : z); }

    constexpr Vec3T operator+(const Vec3T& o) const { return {x + o.x, y + o.y, z + o.z}; }
    constexpr Vec3T operator-(const Vec3T& o) const { return {x - o.x, y - o.y, z - o.z}; }
    constexpr Vec3T operator-() const { return {-x, -y, -z}; }
    constexpr Vec3T operator*(T s) const { return {x * s, y * s, z * s}; }
    constexpr Vec3T operator/(T s) const { return {x / s, y / s, z / s}; }
    constexpr Vec3T& operator+=(const Vec3T& o) {
        x += o.x;
        y += o.y;
        z += o.z;
        return *this;
    }
    constexpr Vec3T& operator-=(const Vec3T& o) {
        x -= o.x;
        y -= o.y;
        z -= o.z;
        return *this;
    }
    constexpr Vec3T& operator*=(T s) {
        x *= s;
        y *= s;
        z *= s;
        return *this;
    }
    constexpr bool operator==(const Vec3T& o) const = default;
};

template <typename T> constexpr Vec3T<T> operator*(T s, const Vec3T<T>& v) {
    return v * s;
}

template <typename T> constexpr T dot(const Vec3T<T>& a, const Vec3T<T>& b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

template <typename T> constexpr Vec3T<T> cross(const Vec3T<T>& a, const Vec3T<T>& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

template <typename T> inline T length(const Vec3T<T>& v) {
    return std::sqrt(dot(v, v));
}

template <typename T> inline Vec3T<T> normalize(const Vec3T<T>& v) {
    T len = length(v);
    return len > T(0) ? v / len : v;
}

template <typename T> inline bool is_finite(const Vec3T<T>& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

template <typename T> inline Vec3T<T> min(const Vec3T<T>& a, const Vec3T<T>& b) {
    return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)};
}

template <typename T> inline Vec3T<T> max(const Vec3T<T>& a, const Vec3T<T>& b) {
    return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)};
}

using Vec3 = Vec3T<double>;
using Vec3f = Vec3T<float>;

struct Vec2 {
    double x = 0, y = 0;
};

inline Vec2 operator+(const Vec2& a, const Vec2& b) {
    return {a.x + b.x, a.y + b.y};
}
inline Vec2 operator-(const Vec2& a, const Vec2& b) {
    return {a.x - b.x, a.y - b.y};
}
inline Vec2 operator*(const Vec2& a, double s) {
    return {a.x * s, a.y * s};
}
inline double dot(const Vec2& a, const Vec2& b) {
    return a.x * b.x + a.y * b.y;
}
/// The z component of the 3D cross product: twice the signed area of (0, a, b).
inline double cross(const Vec2& a, const Vec2& b) {
    return a.x * b.y - a.y * b.x;
}
inline double length(const Vec2& a) {
    return std::sqrt(dot(a, a));
}

/// Axis-aligned bounding box.
struct BBox {
    Vec3 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
            std::numeric_limits<double>::infinity()};
    Vec3 hi{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
            -std::numeric_limits<double>::infinity()};

    void extend(const Vec3& p) {
        lo = min(lo, p);
        hi = max(hi, p);
    }
    bool empty() const { return lo.x > hi.x; }
    double diagonal() const { return empty() ? 0.0 : length(hi - lo); }
};

/// Orthonormal frame around a unit normal (z axis = n), after Duff et al. 2017.
struct Frame {
    Vec3 s, t, n;

    static Frame from_normal(const Vec3& n) {
        double sign = std::copysign(1.0, n.z);
        double a = -1.0 / (sign + n.z);
        double b = n.x * n.y * a;
        return {Vec3(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
                Vec3(b, sign + n.y * n.y * a, -n.y), n};
    }
    Vec3 to_world(const Vec3& v) const { return s * v.x + t * v.y + n * v.z; }
    Vec3 to_local(const Vec3& v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
};

inline constexpr double k_pi = 3.14159265358979323846;
inline constexpr double k_inv_pi = 1.0 / k_pi;

} // namespace penumbra

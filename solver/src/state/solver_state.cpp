// Binary file of a hierarchical solve's state (see state/solver_state.h): a magic word and version,
// then the fields in order, each vector as its element count and raw elements, then a 64-bit
// checksum of all the bytes before it. Both directions stream: the checksum is computed as the
// fields go to or come from the file, so no second copy of the links is ever held.

#include "state/solver_state.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <optional>
#include <span>
#include <string_view>

#include "core/error.h"
#include "core/files.h"
#include "core/rng.h"

namespace penumbra::solver {

namespace {

// Version 4: cluster links index the face-cluster tree, and their kernels are calibrated.
// Version 5: element links are 16 bytes (the occlusion flag is the spread's sign bit).
// Version 8: cluster links are 32 bytes (their visible fraction in 16 bits).
// Version 9: a checksum follows the fields, so that a corrupted file is refused, not solved.
constexpr char k_magic[8] = {'P', 'N', 'B', 'R', 'H', 'R', 'S', '9'};

/// state_checksum() of bytes that arrive in pieces of any size.
class StateChecksum {
public:
    /// The hash starts from the total size, so it must be known before the first byte.
    explicit StateChecksum(std::uint64_t total_bytes) : h_(hash_words({total_bytes})) {}

    void add(const void* data, std::size_t size) {
        if (size == 0) // an empty array's data() may be null, which memcpy must not see
            return;
        const char* bytes = static_cast<const char*>(data);
        if (pending_ > 0) { // complete the word an earlier piece began
            const std::size_t n = std::min(size, sizeof(std::uint64_t) - pending_);
            std::memcpy(partial_.data() + pending_, bytes, n);
            pending_ += n;
            bytes += n;
            size -= n;
            if (pending_ < sizeof(std::uint64_t))
                return;
            add_word(partial_.data());
            pending_ = 0;
        }
        while (size >= sizeof(std::uint64_t)) {
            add_word(bytes);
            bytes += sizeof(std::uint64_t);
            size -= sizeof(std::uint64_t);
        }
        std::memcpy(partial_.data(), bytes, size);
        pending_ = size;
    }

    /// The checksum; a last partial word counts as if padded with zero bytes.
    std::uint64_t value() const {
        std::uint64_t h = h_;
        if (pending_ > 0) {
            std::array<char, sizeof(std::uint64_t)> last{};
            std::memcpy(last.data(), partial_.data(), pending_);
            h = mix(h, last.data());
        }
        return h;
    }

private:
    static std::uint64_t mix(std::uint64_t h, const char* word_bytes) {
        std::uint64_t word = 0;
        std::memcpy(&word, word_bytes, sizeof(word));
        return mix64(h ^ mix64(word + 0x632be59bd9b4e019ULL));
    }
    void add_word(const char* word_bytes) { h_ = mix(h_, word_bytes); }

    std::uint64_t h_;
    std::array<char, sizeof(std::uint64_t)> partial_{};
    std::size_t pending_ = 0;
};

/// Counts the bytes of the fields: the checksum starts from their total.
struct ByteCounter {
    std::uint64_t bytes = 0;
    void write(const void*, std::size_t size) { bytes += size; }
};

/// Writes the fields to the file and hashes them on the way.
struct HashingFile {
    FileWriter& file;
    StateChecksum& checksum;
    void write(const void* data, std::size_t size) {
        checksum.add(data, size);
        file.write(data, size);
    }
};

template <typename Sink> class Writer {
public:
    explicit Writer(Sink& out) : out_(out) {}
    void bytes(const void* data, std::size_t size) { out_.write(data, size); }
    template <typename T> void pod(const T& value) { bytes(&value, sizeof(T)); }
    template <typename T> void vec(std::span<const T> values) {
        pod(std::uint64_t(values.size()));
        bytes(values.data(), values.size() * sizeof(T));
    }
    template <typename T> void vec(const std::vector<T>& values) {
        vec(std::span<const T>(values));
    }

private:
    Sink& out_;
};

/// Every field of the state after the magic word, in file order (read_hierarchical_state reads
/// them back in the same order).
template <typename Sink> void write_fields(Writer<Sink>& w, const HierarchicalState& s) {
    w.pod(s.mesh_hash);
    w.pod(std::uint8_t(s.clustered ? 1 : 0));
    const Hierarchy& h = s.hierarchy;
    w.pod(std::uint64_t(h.root_count));
    w.pod(h.diagonal);
    w.vec(h.triangle);
    w.vec(h.normal);
    w.vec(h.area);
    w.vec(h.patch);
    w.vec(h.parent);
    w.vec(h.first_child);
    w.vec(h.level);
    w.vec(h.twin);
    w.vec(s.links.span());
    w.vec(s.cluster_links.span());
    w.vec(s.radiosity);
    w.vec(s.weights.offset);
    w.vec(s.weights.receive);
    w.vec(s.weights.emit);
    w.vec(s.weights.raw_receive);
    w.vec(s.weights.raw_emit);
    w.vec(s.weights.signature);
}

[[noreturn]] void fail_not_a_state(const std::string& path, const std::string& what) {
    throw InputError(path, "",
                     "not a Penumbra solver state (" + what +
                         "): bake again with the hierarchical method");
}

/// Reads the fields straight from the file into their arrays, hashing them on the way. A
/// corrupted file is reported as such ("checksum mismatch") whichever check sees it first: a
/// failed size check hashes the rest of the file before it reports.
class Reader {
public:
    explicit Reader(const std::string& path) : path_(path), in_(path, std::ios::binary) {
        if (!in_)
            throw InputError(path, "",
                             "cannot open the solver state (bake with the hierarchical "
                             "method first; it writes solver_state.bin)");
        in_.seekg(0, std::ios::end);
        const auto size = std::uint64_t(std::streamoff(in_.tellg()));
        in_.seekg(0);
        check_magic(size);
        payload_ = size - sizeof(std::uint64_t);
        checksum_.emplace(payload_);
        checksum_->add(k_magic, sizeof(k_magic));
        at_ = sizeof(k_magic);
    }
    template <typename T> T pod() {
        T value;
        take(&value, sizeof(T));
        return value;
    }
    template <typename T> std::vector<T> vec() {
        std::vector<T> values(count<T>());
        take(values.data(), values.size() * sizeof(T));
        return values;
    }
    template <typename T> void vec(MappedArray<T>& values) {
        values.resize(count<T>());
        take(values.data(), values.size() * sizeof(T));
    }
    bool done() const { return at_ == payload_; }
    /// Refuses the file if the checksum at its end is not that of the bytes before it.
    void verify_checksum() {
        if (verified_)
            return;
        std::array<char, 1 << 16> scratch;
        while (at_ < payload_)
            take(scratch.data(),
                 std::size_t(std::min<std::uint64_t>(scratch.size(), payload_ - at_)));
        std::uint64_t stored = 0;
        read(&stored, sizeof(stored));
        if (stored != checksum_->value())
            throw InputError(path_, "", "is corrupt (checksum mismatch): bake without --reuse");
        verified_ = true;
    }
    [[noreturn]] void fail(const std::string& what) {
        verify_checksum();
        fail_not_a_state(path_, what);
    }

private:
    /// Refuses another version's file and a file that is not a state, before any other check.
    void check_magic(std::uint64_t size) {
        if (size < sizeof(k_magic))
            fail_not_a_state(path_, "truncated or corrupt");
        char magic[sizeof(k_magic)];
        read(magic, sizeof(magic));
        if (std::memcmp(magic, k_magic, sizeof(k_magic) - 1) == 0 &&
            magic[sizeof(k_magic) - 1] != k_magic[sizeof(k_magic) - 1])
            fail_not_a_state(path_,
                             "written by another version of penumbra: bake again without --reuse");
        if (std::memcmp(magic, k_magic, sizeof(k_magic)) != 0)
            fail_not_a_state(path_, "bad magic word");
        if (size < sizeof(k_magic) + sizeof(std::uint64_t))
            fail_not_a_state(path_, "truncated or corrupt");
    }
    /// The element count of the array that follows, checked against what is left.
    template <typename T> std::size_t count() {
        const auto n = pod<std::uint64_t>();
        if (n > (payload_ - at_) / sizeof(T))
            fail("truncated or corrupt");
        return std::size_t(n);
    }
    void take(void* out, std::size_t n) {
        if (n > payload_ - at_)
            fail("truncated or corrupt");
        if (n == 0) // an empty array's data() may be null
            return;
        read(out, n);
        checksum_->add(out, n);
        at_ += n;
    }
    void read(void* out, std::size_t n) {
        errno = 0;
        if (!in_.read(static_cast<char*>(out), std::streamsize(n)))
            throw InputError(path_, "",
                             std::string("cannot read the solver state: ") +
                                 (errno ? std::strerror(errno) : "read failed"));
    }

    std::string path_;
    std::ifstream in_;
    std::uint64_t payload_ = 0; ///< bytes before the checksum
    std::uint64_t at_ = 0;
    std::optional<StateChecksum> checksum_;
    bool verified_ = false;
};

} // namespace

// Chained mix64 of the bytes' 64-bit words and their count. Each step is a bijection of the
// running hash, so a change confined to one word always changes the result.
std::uint64_t state_checksum(std::string_view bytes) {
    StateChecksum checksum(bytes.size());
    checksum.add(bytes.data(), bytes.size());
    return checksum.value();
}

std::uint64_t mesh_geometry_hash(const RadiosityMesh& mesh) {
    std::uint64_t h = hash_words({mesh.element_count(), mesh.vertex_count()});
    auto add = [&h](std::uint64_t w) { h = mix64(h ^ mix64(w + 0x632be59bd9b4e019ULL)); };
    for (std::size_t e = 0; e < mesh.element_count(); ++e) {
        for (std::uint32_t v : mesh.triangles[e]) {
            const Vec3 p = mesh.vertex(v);
            add(std::bit_cast<std::uint64_t>(p.x));
            add(std::bit_cast<std::uint64_t>(p.y));
            add(std::bit_cast<std::uint64_t>(p.z));
        }
        add(mesh.element_patch[e]);
        add(std::uint64_t(std::int64_t(mesh.element_twin[e])));
    }
    return h;
}

void write_hierarchical_state(const HierarchicalState& s, const std::string& path) {
    ByteCounter counter;
    Writer<ByteCounter> count(counter);
    write_fields(count, s);
    write_atomically(path, [&](const std::string& temp) {
        FileWriter file(temp, path);
        StateChecksum checksum(sizeof(k_magic) + counter.bytes);
        HashingFile out{file, checksum};
        Writer<HashingFile> w(out);
        w.bytes(k_magic, sizeof(k_magic));
        write_fields(w, s);
        const std::uint64_t sum = checksum.value();
        file.write(&sum, sizeof(sum));
        file.close();
    });
}

std::shared_ptr<const HierarchicalState> read_hierarchical_state(const std::string& path) {
    Reader r(path);
    auto s = std::make_shared<HierarchicalState>();
    s->mesh_hash = r.pod<std::uint64_t>();
    s->clustered = r.pod<std::uint8_t>() != 0;
    Hierarchy& h = s->hierarchy;
    h.root_count = std::size_t(r.pod<std::uint64_t>());
    h.diagonal = r.pod<double>();
    h.triangle = r.vec<std::array<Vec3, 3>>();
    h.normal = r.vec<Vec3>();
    h.area = r.vec<double>();
    h.patch = r.vec<std::uint32_t>();
    h.parent = r.vec<std::int32_t>();
    h.first_child = r.vec<std::int32_t>();
    h.level = r.vec<std::int32_t>();
    h.twin = r.vec<std::int32_t>();
    r.vec(s->links);
    r.vec(s->cluster_links);
    s->radiosity = r.vec<Rgb>();
    LeafWeights& lw = s->weights;
    lw.offset = r.vec<std::uint32_t>();
    lw.receive = r.vec<float>();
    lw.emit = r.vec<float>();
    lw.raw_receive = r.vec<float>();
    lw.raw_emit = r.vec<float>();
    lw.signature = r.vec<std::uint64_t>();
    const bool all_read = r.done();
    r.verify_checksum();
    const std::size_t n = h.triangle.size();
    const std::size_t entries = lw.offset.empty() ? 0 : lw.offset.back();
    const bool weights_consistent =
        lw.offset.empty()
            ? lw.receive.empty() && lw.signature.empty()
            : lw.offset.size() == n + 1 && lw.receive.size() == entries &&
                  lw.emit.size() == entries && lw.raw_receive.size() == entries &&
                  lw.raw_emit.size() == entries && lw.signature.size() == n &&
                  h.first_child.size() == n && h.level.size() == n && [&] {
                      for (std::size_t x = 0; x < n; ++x) // a leaf: one entry per ancestor
                          if (lw.offset[x + 1] - lw.offset[x] !=
                              std::uint32_t(h.first_child[x] < 0 ? h.level[x] : 0))
                              return false;
                      return true;
                  }();
    const bool consistent = h.normal.size() == n && h.area.size() == n && h.patch.size() == n &&
                            h.parent.size() == n && h.first_child.size() == n &&
                            h.level.size() == n && h.twin.size() == n && s->radiosity.size() == n &&
                            h.root_count <= n && weights_consistent && all_read;
    if (!consistent)
        r.fail("inconsistent sizes");
    const auto in_range = [n](std::uint32_t node) { return node < n; };
    for (const Link& l : s->links)
        if (!in_range(l.receiver) || !in_range(l.source))
            r.fail("link to a missing node");
    h.emission.assign(n, Rgb{});
    h.reflectance.assign(n, Rgb{});
    h.transmittance.assign(n, Rgb{});
    h.opaque.assign(n, 1);
    h.specular_only.assign(n, 0);
    return s;
}

} // namespace penumbra::solver

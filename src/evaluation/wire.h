// Values packed into bytes and back, for what ranks send each other (Team::gather, broadcast):
// trivially copyable values as their bytes, strings and vectors with their length first. Both
// ends are the same binary on machines of one kind, so no byte order or layout is negotiated.
#pragma once
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace tripath::evaluation {

class WireWriter {
public:
    template <class T>
        requires std::is_trivially_copyable_v<T>
    WireWriter& put(const T& v) {
        bytes_.append(reinterpret_cast<const char*>(&v), sizeof(T));
        return *this;
    }
    WireWriter& put(const std::string& s) {
        put(uint64_t(s.size()));
        bytes_ += s;
        return *this;
    }
    template <class T>
    WireWriter& put(const std::vector<T>& v) {
        put(uint64_t(v.size()));
        for (const T& x : v) put(x);
        return *this;
    }
    const std::string& bytes() const { return bytes_; }

private:
    std::string bytes_;
};

class WireReader {
public:
    explicit WireReader(const std::string& bytes) : bytes_(bytes) {}
    template <class T>
        requires std::is_trivially_copyable_v<T>
    void get(T& v) {
        take(&v, sizeof(T));
    }
    void get(std::string& s) {
        uint64_t n = 0;
        get(n);
        s.resize(n);
        take(s.data(), n);
    }
    template <class T>
    void get(std::vector<T>& v) {
        uint64_t n = 0;
        get(n);
        v.resize(n);
        for (T& x : v) get(x);
    }
    bool done() const { return at_ == bytes_.size(); }

private:
    void take(void* out, size_t n) {
        if (bytes_.size() - at_ < n) throw std::runtime_error("a message between ranks was cut short");
        std::memcpy(out, bytes_.data() + at_, n);
        at_ += n;
    }
    const std::string& bytes_;
    size_t at_ = 0;
};

}  // namespace tripath::evaluation

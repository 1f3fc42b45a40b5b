#include "images/jpeg_guard.h"

#include <fmt/format.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <vector>

namespace kdop {
namespace {

// What OpenImageIO 2.4 reads of an APP13 segment's bytes `data`: "Photoshop 3.0" and its NUL,
// "8BIM", the resource id (0x0404 for IPTC), 4 bytes it skips, and the block's 16-bit size, then
// that many bytes. Why that overruns the segment, or nothing.
std::optional<std::string> overrun(const std::vector<unsigned char>& data) {
    static constexpr char kPhotoshop[] = "Photoshop 3.0"; // with its NUL: 14 bytes
    const std::size_t n = data.size();
    // strcmp on the segment: it stops at the first difference, or reads on where the segment is a
    // proper prefix of the signature (its NUL missing).
    for (std::size_t i = 0; i < sizeof kPhotoshop; ++i) {
        if (i == n)
            return fmt::format("its APP13 segment ends after {} bytes, inside the \"Photoshop 3.0\" signature", n);
        if (data[i] != static_cast<unsigned char>(kPhotoshop[i])) return std::nullopt;
    }
    const std::size_t header = sizeof kPhotoshop + 4 + 2 + 4 + 2; // up to and including the size
    for (std::size_t i = sizeof kPhotoshop; i < std::min(n, sizeof kPhotoshop + 4); ++i)
        if (data[i] != static_cast<unsigned char>("8BIM"[i - sizeof kPhotoshop])) return std::nullopt;
    if (n >= sizeof kPhotoshop + 6 && (data[18] << 8 | data[19]) != 0x0404) return std::nullopt;
    if (n < header)
        return fmt::format("its APP13 segment ends after {} bytes, inside its IPTC block's header ({} bytes)", n,
                           header);
    const std::size_t claimed = std::size_t(data[24]) << 8 | data[25];
    if (header + claimed > n)
        return fmt::format("its APP13 segment's IPTC block claims {} bytes, and the segment holds {}", claimed,
                           n - header);
    return std::nullopt;
}

} // namespace

std::optional<std::string> unsafe_jpeg_metadata(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    unsigned char soi[3] = {0, 0, 0};
    if (!in.read(reinterpret_cast<char*>(soi), 3) || soi[0] != 0xFF || soi[1] != 0xD8 || soi[2] != 0xFF)
        return std::nullopt; // not a JPEG
    in.seekg(2);
    // Marker after marker until the scan: FF, its code, and (for all but the standalone ones) a
    // 16-bit length that counts itself.
    for (;;) {
        int byte = in.get();
        if (byte != 0xFF) return std::nullopt; // damaged: the decoder reports it
        int code = in.get();
        while (code == 0xFF) code = in.get();                                 // fill bytes
        if (code == EOF || code == 0xD9 || code == 0xDA) return std::nullopt; // the end, or the scan
        if (code == 0x01 || (code >= 0xD0 && code <= 0xD7)) continue;         // no length
        const int high = in.get(), low = in.get();
        if (high == EOF || low == EOF) return std::nullopt;
        const int length = high << 8 | low;
        if (length < 2) return std::nullopt;
        if (code != 0xED) { // not APP13
            in.seekg(length - 2, std::ios::cur);
            if (!in) return std::nullopt;
            continue;
        }
        std::vector<unsigned char> data(std::size_t(length) - 2);
        in.read(reinterpret_cast<char*>(data.data()), std::streamsize(data.size()));
        data.resize(std::size_t(in.gcount())); // a file cut short: the segment is what is there
        if (auto why = overrun(data)) return why;
        if (!in) return std::nullopt;
    }
}

} // namespace kdop

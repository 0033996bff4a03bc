#pragma once
// Where write_exr's bytes go: a file written in 64 KiB blocks. OpenEXR's own file stream goes
// through std::ofstream, which hands the kernel one uncompressed scanline (3 KiB at 256 pixels)
// per call: 257 calls a 256x256 frame (13 now), and at 192 frames the kernel's work per call
// cost more CPU than the rest of the EXR writer. The bytes are the same; only the calls differ.
#include <OpenEXR/ImfIO.h>

#include <cstdint>
#include <memory>
#include <string>

namespace sl {

class ExrFileStream final : public Imf::OStream {
public:
    // Creates (or truncates) `path`. Throws std::runtime_error naming the system's reason.
    explicit ExrFileStream(const std::string& path);
    ~ExrFileStream() override;  // closes without reporting: call close() to know it worked
    ExrFileStream(const ExrFileStream&) = delete;
    ExrFileStream& operator=(const ExrFileStream&) = delete;

    void write(const char c[], int n) override;
    uint64_t tellp() override { return pos_; }
    void seekp(uint64_t pos) override { pos_ = pos; }  // the next write starts a new block there

    // Writes what is buffered and closes the file; throws std::runtime_error on failure.
    void close();

private:
    void flush();

    int fd_ = -1;
    std::string path_;
    std::unique_ptr<char[]> buffer_;  // one block
    uint64_t buffer_at_ = 0;  // file offset of buffer_[0]
    uint64_t buffered_ = 0;   // bytes in buffer_
    uint64_t pos_ = 0;        // where the next write() goes
};

}  // namespace sl

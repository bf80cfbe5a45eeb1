#include "gcode/transform/join_stream.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include <fmt/format.h>

namespace gcode {

struct JoinStream::TextSink : SpliceSink {
  explicit TextSink(std::string& text) : text(text) {}
  void line(std::string_view line) override {
    text.append(line);
    text.push_back('\n');
  }
  // The text is read again by a pipeline of its own, which finds the layers
  // and the end code from the file's own markers.
  void layer(const LayerInfo&, const MachineState&) override {}
  void end_code(const EndCodeInfo&, const MachineState&) override {}
  std::string& text;
};

JoinStream::JoinStream(const std::string& path) : path_(path) {
  fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd_ < 0) throw std::runtime_error(fmt::format("cannot open {}: {}", path, std::strerror(errno)));
  struct stat st{};
  if (::fstat(fd_, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd_);
    fd_ = -1;
    throw std::runtime_error(fmt::format("{} is not a regular file (it is read by layer)", path));
  }
  index_ = std::make_unique<LayerIndex>(fd_, path, markers_);
}

JoinStream::~JoinStream() {
  stream_.reset();
  index_.reset();
  if (fd_ >= 0) ::close(fd_);
}

void JoinStream::plan(const StreamPoint& printed, int z_decimals, const std::string& onto, Diagnostics* diag) {
  if (stream_ || next_block_ > 0) throw std::logic_error("JoinStream::plan after the first pump");
  if (diag != nullptr && !index_->e_mode_warning().empty()) diag->warn(index_->e_mode_warning());
  blocks_ = join_blocks(*index_, printed.top_z, z_decimals, printed.extent, onto, std::string(), diag);
  printed_ = printed;
  planned_ = true;
}

std::uint64_t JoinStream::bytes() const {
  if (!planned_ || blocks_.blocks.empty()) return 0;
  struct stat st{};
  if (::fstat(fd_, &st) != 0) return 0;
  std::uint64_t size = static_cast<std::uint64_t>(st.st_size);
  std::uint64_t begin = blocks_.blocks.back().begin;
  for (const SpliceBlock& b : blocks_.blocks) begin = std::min(begin, b.begin);
  return size > begin ? size - begin : 0;
}

bool JoinStream::pump(std::string& text, const SeamOptions& options, const Precision& precision, Diagnostics* diag) {
  if (!planned_) throw std::logic_error("JoinStream::pump before plan");
  TextSink sink(text);
  const std::size_t before = text.size();
  while (next_block_ < blocks_.blocks.size()) {
    if (!stream_) {
      // Only the first block's seam tells of another E mode: the rest are
      // the same file.
      stream_ = std::make_unique<BlockStream>(blocks_.blocks[next_block_], printed_, options, precision,
                                              next_block_ == 0 ? diag : nullptr);
    }
    bool more = stream_->pump(sink);
    if (!more) {
      stream_.reset();
      ++next_block_;
    }
    if (text.size() > before) break;
  }
  bytes_out_ = std::min(bytes(), bytes_out_ + (text.size() - before));
  return text.size() > before || next_block_ < blocks_.blocks.size();
}

}  // namespace gcode

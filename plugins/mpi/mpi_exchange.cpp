// The MPI side of a distributed render, built as a plugin (libslowlight_mpi.so) that the
// program loads only when an MPI launcher started it: a plain run never loads MPI at all.
// Standard MPI-3 calls only, so that it builds and runs with Open MPI and MPICH alike.
// The C interface only: the C++ bindings (deprecated) would need their own library.
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>

#include <time.h>

#include <algorithm>
#include <climits>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "stages/render/rank_exchange.h"

namespace {

class MpiExchange final : public sl::RankExchange {
public:
    MpiExchange() {
        MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
        MPI_Comm_size(MPI_COMM_WORLD, &size_);
        // Errors come back as return codes: a lost rank ends the job with our own error line.
        MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
        for (MPI_Comm& c : comm_) {
            check(MPI_Comm_dup(MPI_COMM_WORLD, &c), "MPI_Comm_dup");
            MPI_Comm_set_errhandler(c, MPI_ERRORS_RETURN);
        }
        MPI_Comm node;  // the ranks that share this rank's memory
        check(MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node),
              "MPI_Comm_split_type");
        int node_size = 0;
        MPI_Comm_size(node, &node_size);
        MPI_Comm_free(&node);
        // SLOWLIGHT_RANKS_AS_NODES=1 makes ranks on one machine behave as if each had its own
        // (each sorts the whole photon map): how the tests run the several-machines path here.
        const char* as_nodes = std::getenv("SLOWLIGHT_RANKS_AS_NODES");
        const bool forced_apart = as_nodes && std::string(as_nodes) == "1";
        int local = node_size == size_ && !forced_apart ? 1 : 0, all_local = 0;  // the same answer on every rank
        check(MPI_Allreduce(&local, &all_local, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD), "MPI_Allreduce");
        one_node = all_local != 0;
    }
    ~MpiExchange() override {
        for (std::unique_ptr<Window>& w : shared_) w.reset();  // before their communicators
        for (MPI_Comm& c : comm_) MPI_Comm_free(&c);
        MPI_Finalize();
    }
    int rank() const override { return rank_; }
    int ranks() const override { return size_; }

    void all_gather_in_place(sl::Channel ch, void* data, uint64_t element_bytes,
                             const std::vector<uint64_t>& bounds) override {
        MPI_Comm c = comm(ch);
        // One element is one MPI item: the counts and displacements (ints) then reach 2^31
        // elements, not 2 GiB.
        MPI_Datatype element;
        check(MPI_Type_contiguous(to_int(element_bytes), MPI_BYTE, &element), "MPI_Type_contiguous");
        check(MPI_Type_commit(&element), "MPI_Type_commit");
        std::vector<int> n, at;
        for (int r = 0; r < size_; ++r) {
            n.push_back(to_int(bounds[static_cast<size_t>(r) + 1] - bounds[static_cast<size_t>(r)]));
            at.push_back(to_int(bounds[static_cast<size_t>(r)]));
        }
        MPI_Request q;
        const double t0 = MPI_Wtime();
        check(MPI_Iallgatherv(MPI_IN_PLACE, 0, MPI_DATATYPE_NULL, data, n.data(), at.data(), element, c, &q),
              "MPI_Iallgatherv");
        wait(q, "MPI_Iallgatherv");
        transfer_seconds[static_cast<int>(ch)] += MPI_Wtime() - t0;
        MPI_Type_free(&element);
        const uint64_t mine = static_cast<uint64_t>(n[static_cast<size_t>(rank_)]) * element_bytes;
        count(ch, mine * static_cast<uint64_t>(size_ - 1), (bounds.back() - bounds.front()) * element_bytes - mine);
    }

    void gather(sl::Channel ch, const void* mine, uint64_t bytes, std::vector<char>& all,
                std::vector<uint64_t>& counts) override {
        MPI_Comm c = comm(ch);
        counts.assign(static_cast<size_t>(size_), 0);
        MPI_Request q;
        check(MPI_Igather(&bytes, 1, MPI_UINT64_T, counts.data(), 1, MPI_UINT64_T, 0, c, &q), "MPI_Igather");
        wait(q, "MPI_Igather");
        std::vector<int> n, at;
        uint64_t total = bytes;
        if (rank_ == 0) {
            total = displacements(counts, n, at);
            all.resize(total);
        } else {
            all.clear();
        }
        const double t0 = MPI_Wtime();
        check(MPI_Igatherv(mine, to_int(bytes), MPI_BYTE, all.data(), n.data(), at.data(), MPI_BYTE, 0, c, &q),
              "MPI_Igatherv");
        wait(q, "MPI_Igatherv");
        transfer_seconds[static_cast<int>(ch)] += MPI_Wtime() - t0;
        if (rank_ == 0) count(ch, 0, total - bytes);
        else count(ch, bytes, 0);
    }

    double max(sl::Channel ch, double v) override {
        double out = v;
        allreduce(&v, &out, 1, MPI_DOUBLE, MPI_MAX, comm(ch));
        count(ch, 8, 8);
        return out;
    }
    void max(sl::Channel ch, double* values, int n) override {
        allreduce(MPI_IN_PLACE, values, n, MPI_DOUBLE, MPI_MAX, comm(ch));
        count(ch, 8u * static_cast<uint64_t>(n), 8u * static_cast<uint64_t>(n));
    }
    int max(sl::Channel ch, int v) override {
        int out = v;
        allreduce(&v, &out, 1, MPI_INT, MPI_MAX, comm(ch));
        count(ch, 4, 4);
        return out;
    }
    void sum(sl::Channel ch, uint64_t* values, int n) override {
        allreduce(MPI_IN_PLACE, values, n, MPI_UINT64_T, MPI_SUM, comm(ch));
        count(ch, 8u * static_cast<uint64_t>(n), 8u * static_cast<uint64_t>(n));
    }
    bool broadcast(sl::Channel ch, bool v) override {
        int x = v ? 1 : 0;
        bcast(&x, 1, MPI_INT, comm(ch));
        count(ch, rank_ == 0 ? 4 : 0, rank_ == 0 ? 0 : 4);
        return x != 0;
    }
    double broadcast(sl::Channel ch, double v) override {
        bcast(&v, 1, MPI_DOUBLE, comm(ch));
        count(ch, rank_ == 0 ? 8 : 0, rank_ == 0 ? 0 : 8);
        return v;
    }
    void broadcast(sl::Channel ch, std::vector<char>& bytes) override {
        MPI_Comm c = comm(ch);
        uint64_t n = bytes.size();
        bcast(&n, 1, MPI_UINT64_T, c);
        bytes.resize(n);
        bcast(bytes.data(), to_int(n), MPI_BYTE, c);
        count(ch, rank_ == 0 ? n * static_cast<uint64_t>(size_ - 1) : 0, rank_ == 0 ? 0 : n);
    }
    void scatter(sl::Channel ch, const std::vector<char>& all, const std::vector<uint64_t>& counts,
                 std::vector<char>& mine) override {
        MPI_Comm c = comm(ch);
        uint64_t n = 0;
        MPI_Request q;
        check(MPI_Iscatter(counts.data(), 1, MPI_UINT64_T, &n, 1, MPI_UINT64_T, 0, c, &q), "MPI_Iscatter");
        wait(q, "MPI_Iscatter");
        mine.resize(n);
        std::vector<int> sizes, at;
        uint64_t total = 0;
        if (rank_ == 0) total = displacements(counts, sizes, at);
        check(MPI_Iscatterv(all.data(), sizes.data(), at.data(), MPI_BYTE, mine.data(), to_int(n), MPI_BYTE, 0, c, &q),
              "MPI_Iscatterv");
        wait(q, "MPI_Iscatterv");
        if (rank_ == 0) count(ch, total - n, 0);
        else count(ch, 0, n);
    }
    sl::SharedBlocks& shared(sl::Shared which, sl::Channel ch) override {
        std::unique_ptr<Window>& w = shared_[static_cast<int>(which)];
        if (!w) w = std::make_unique<Window>(*this, ch);
        return *w;
    }
    [[noreturn]] void abort(int code) override {
        std::fflush(stderr);
        MPI_Abort(MPI_COMM_WORLD, code);
        std::_Exit(code);  // MPI_Abort does not return; should it, the process still ends
    }

private:
    // A shared-memory window (MPI_Win_allocate_shared) holding one block per rank, reallocated,
    // by every rank at once, when a rank asks for more than its block holds. Every rank keeps a
    // passive access epoch open on it (lock_all), so that MPI_Win_sync orders its loads and
    // stores around the barriers of fence().
    class Window final : public sl::SharedBlocks {
    public:
        Window(MpiExchange& ex, sl::Channel ch)
            : ex_(ex), ch_(ch), asked_(static_cast<size_t>(ex.size_), 0), capacity_(asked_), block_(asked_.size()) {}
        ~Window() override { release(); }
        void reserve(uint64_t bytes) override {
            std::fill(asked_.begin(), asked_.end(), 0);
            asked_[static_cast<size_t>(ex_.rank_)] = bytes;
            ex_.sum(ch_, asked_.data(), ex_.size_);
            bool grow = win_ == MPI_WIN_NULL;
            for (size_t r = 0; r < asked_.size(); ++r) grow |= asked_[r] > capacity_[r];
            // What the other ranks' blocks hold is what this rank reads of them: the bytes that
            // a message would have carried.
            uint64_t others = 0;
            for (size_t r = 0; r < asked_.size(); ++r) others += r == static_cast<size_t>(ex_.rank_) ? 0 : asked_[r];
            ex_.count(ch_, bytes * static_cast<uint64_t>(ex_.size_ - 1), others);
            if (!grow) return;
            release();
            // 1/16 spare and whole pages: the sizes move a little from pass to pass.
            for (size_t r = 0; r < asked_.size(); ++r)
                if (asked_[r] > capacity_[r]) capacity_[r] = (asked_[r] + asked_[r] / 16 + 4095) / 4096 * 4096;
            MPI_Info info;
            MPI_Info_create(&info);
            MPI_Info_set(info, "alloc_shared_noncontig", "true");  // each block on its own pages
            void* base = nullptr;
            const int rc = MPI_Win_allocate_shared(static_cast<MPI_Aint>(capacity_[static_cast<size_t>(ex_.rank_)]), 1,
                                                   info, ex_.comm(ch_), &base, &win_);
            MPI_Info_free(&info);
            if (rc != MPI_SUCCESS) {  // most often: the shared-memory file system is too small
                std::fprintf(stderr,
                             "error: rank %d of %d: cannot map %.1f MiB of memory shared with the other ranks of this "
                             "machine (MPI_Win_allocate_shared failed; is /dev/shm large enough?); "
                             "SLOWLIGHT_RANKS_AS_NODES=1 copies the photons between the ranks instead\n",
                             ex_.rank_, ex_.size_,
                             static_cast<double>(capacity_[static_cast<size_t>(ex_.rank_)]) / (1024.0 * 1024.0));
                ex_.abort(1);
            }
            MPI_Win_set_errhandler(win_, MPI_ERRORS_RETURN);
            ex_.check(MPI_Win_lock_all(MPI_MODE_NOCHECK, win_), "MPI_Win_lock_all");
            for (int r = 0; r < ex_.size_; ++r) {
                MPI_Aint size = 0;
                int unit = 0;
                void* at = nullptr;
                ex_.check(MPI_Win_shared_query(win_, r, &size, &unit, &at), "MPI_Win_shared_query");
                block_[static_cast<size_t>(r)] = static_cast<char*>(at);
                if (reinterpret_cast<uintptr_t>(at) % 8 != 0) {  // records hold doubles
                    std::fprintf(stderr, "error: rank %d of %d: MPI_Win_shared_query gave rank %d's block at an address "
                                         "not aligned to 8 bytes\n", ex_.rank_, ex_.size_, r);
                    ex_.abort(1);
                }
            }
        }
        char* block(int rank) const override { return block_[static_cast<size_t>(rank)]; }
        uint64_t asked(int rank) const override { return asked_[static_cast<size_t>(rank)]; }
        uint64_t capacity(int rank) const override { return capacity_[static_cast<size_t>(rank)]; }
        void fence() override {
            if (win_ != MPI_WIN_NULL) MPI_Win_sync(win_);
            MPI_Request q;
            ex_.check(MPI_Ibarrier(ex_.comm(ch_), &q), "MPI_Ibarrier");
            ex_.wait(q, "MPI_Ibarrier");
            if (win_ != MPI_WIN_NULL) MPI_Win_sync(win_);
        }

    private:
        // Collective, like the allocation: every rank frees the window at the same point (a
        // reallocation, or the end of the job).
        void release() {
            if (win_ == MPI_WIN_NULL) return;
            MPI_Win_unlock_all(win_);
            MPI_Win_free(&win_);
            std::fill(block_.begin(), block_.end(), nullptr);
        }
        MpiExchange& ex_;
        sl::Channel ch_;
        std::vector<uint64_t> asked_, capacity_;
        std::vector<char*> block_;
        MPI_Win win_ = MPI_WIN_NULL;
    };

    // Waits for a collective without keeping the core busy. MPI's own blocking calls poll in a
    // loop (at best calling sched_yield), so a rank that arrives first at a collective burns its
    // core for as long as the slowest rank needs: on a node shared with other work, or with more
    // ranks than cores, that time is taken from the ranks still working. Here the rank polls for
    // a few microseconds, then sleeps between polls (10 us, growing to 200 us): a collective
    // ends at most 0.2 ms later than it would, against passes of tens of milliseconds. Shared
    // memory and TCP progress only inside MPI calls, so each poll also moves the data on.
    void wait(MPI_Request& q, const char* what) {
        int done = 0;
        for (int spin = 0; spin < 64 && !done; ++spin) check(MPI_Test(&q, &done, MPI_STATUS_IGNORE), what);
        long nap_ns = 10000;
        while (!done) {
            timespec nap{0, nap_ns};
            nanosleep(&nap, nullptr);
            nap_ns = std::min(nap_ns * 2, 200000L);
            check(MPI_Test(&q, &done, MPI_STATUS_IGNORE), what);
        }
    }
    void allreduce(const void* in, void* out, int n, MPI_Datatype type, MPI_Op op, MPI_Comm c) {
        MPI_Request q;
        check(MPI_Iallreduce(in, out, n, type, op, c, &q), "MPI_Iallreduce");
        wait(q, "MPI_Iallreduce");
    }
    void bcast(void* data, int n, MPI_Datatype type, MPI_Comm c) {
        MPI_Request q;
        check(MPI_Ibcast(data, n, type, 0, c, &q), "MPI_Ibcast");
        wait(q, "MPI_Ibcast");
    }
    MPI_Comm comm(sl::Channel ch) {
        ++collectives[static_cast<int>(ch)];
        return comm_[static_cast<int>(ch)];
    }
    void count(sl::Channel ch, uint64_t s, uint64_t r) {
        sent[static_cast<int>(ch)] += s;
        received[static_cast<int>(ch)] += r;
    }
    // A failed collective means a rank is gone or the network failed: no rank can go on.
    void check(int rc, const char* what) {
        if (rc == MPI_SUCCESS) return;
        char text[MPI_MAX_ERROR_STRING] = {};
        int len = 0;
        MPI_Error_string(rc, text, &len);
        std::fprintf(stderr, "error: rank %d of %d: %s failed (%s): another rank has stopped or the network failed\n",
                     rank_, size_, what, text);
        abort(1);
    }
    int to_int(uint64_t bytes) {
        if (bytes > static_cast<uint64_t>(INT_MAX)) {
            std::fprintf(stderr, "error: rank %d: %llu bytes in one message, more than MPI's limit of 2 GiB; "
                                 "use more ranks or fewer photons per pass\n",
                         rank_, static_cast<unsigned long long>(bytes));
            abort(1);
        }
        return static_cast<int>(bytes);
    }
    uint64_t displacements(const std::vector<uint64_t>& counts, std::vector<int>& n, std::vector<int>& at) {
        uint64_t total = 0;
        for (uint64_t c : counts) {
            n.push_back(to_int(c));
            at.push_back(to_int(total));
            total += c;
        }
        to_int(total);
        return total;
    }

    int rank_ = 0, size_ = 1;
    MPI_Comm comm_[sl::kChannels] = {MPI_COMM_NULL, MPI_COMM_NULL, MPI_COMM_NULL};
    std::unique_ptr<Window> shared_[sl::kSharedSets];
};

}  // namespace

// Initialises MPI (threads: several TBB workers call it, one per channel at a time) and returns
// the exchange, or null with the reason in `error`. `threads_ok` tells whether the two channels
// may be used at the same time (MPI_THREAD_MULTIPLE).
extern "C" sl::RankExchange* slowlight_mpi_start(int* argc, char*** argv, int* threads_ok, char* error, size_t n) {
    int provided = MPI_THREAD_SINGLE;
    int rc = MPI_Init_thread(argc, argv, MPI_THREAD_MULTIPLE, &provided);
    if (rc != MPI_SUCCESS) {
        std::snprintf(error, n, "MPI_Init_thread failed");
        return nullptr;
    }
    if (provided < MPI_THREAD_SERIALIZED) {
        std::snprintf(error, n, "this MPI library offers no MPI_THREAD_SERIALIZED");
        MPI_Finalize();
        return nullptr;
    }
    *threads_ok = provided >= MPI_THREAD_MULTIPLE ? 1 : 0;
    return new MpiExchange();
}

#include "stages/output/live_temporaries.h"

#include <unistd.h>

#include <atomic>
#include <cstring>

namespace sl {

namespace {

// A lock-free list of heap nodes that only grows: a node is allocated in normal code, pushed
// once, and never freed; a forgotten node is reused for a later temporary whose name fits. So
// the list is as long as the most temporaries ever live at once, and a handler can walk it at
// any moment (no lock, no allocation, no node going away under it).
constexpr uint64_t kFree = 0, kFilling = 1, kLive = 2;  // state: kLive + id once published

struct Node {
    Node* next = nullptr;  // set before the node is pushed, never changed after
    std::atomic<uint64_t> state{kFilling};
    size_t capacity = 0;   // bytes of name, terminator included
    char* name = nullptr;  // written only while state is kFilling
};

std::atomic<Node*> g_head{nullptr};
std::atomic<bool> g_exiting{false};

static_assert(std::atomic<uint64_t>::is_always_lock_free && std::atomic<Node*>::is_always_lock_free &&
              std::atomic<bool>::is_always_lock_free, "a signal handler reads these");

// The exit has begun: a name written now might be missed by the handler's scan, so the caller
// must never get to make its file. Every access is sequentially consistent, so either the scan
// sees this node published or this thread sees g_exiting (and waits here for the _exit).
void wait_if_exiting() {
    if (!g_exiting.load())
        return;
    for (;;) ::pause();
}

}  // namespace

void remember_temporary(uint64_t id, const std::string& path) {
    const size_t need = path.size() + 1;
    for (Node* n = g_head.load(); n; n = n->next) {
        uint64_t expected = kFree;
        if (n->capacity < need || !n->state.compare_exchange_strong(expected, kFilling)) continue;
        wait_if_exiting();  // the handler may be reading this node's old name
        std::memcpy(n->name, path.c_str(), need);
        n->state.store(kLive + id);
        wait_if_exiting();
        return;
    }
    Node* n = new Node;
    n->capacity = need < 256 ? 256 : need;  // room for the longer names that may reuse it
    n->name = new char[n->capacity];
    std::memcpy(n->name, path.c_str(), need);
    n->state.store(kLive + id);
    n->next = g_head.load();
    while (!g_head.compare_exchange_weak(n->next, n)) {
    }
    wait_if_exiting();
}

void forget_temporary(uint64_t id) noexcept {
    for (Node* n = g_head.load(); n; n = n->next) {
        uint64_t expected = kLive + id;
        if (n->state.compare_exchange_strong(expected, kFree)) return;
    }
}

void remove_live_temporaries_and_exit(int status) noexcept {
    g_exiting.store(true);
    for (Node* n = g_head.load(); n; n = n->next)
        if (n->state.load() >= kLive) ::unlink(n->name);
    ::_exit(status);
}

}  // namespace sl

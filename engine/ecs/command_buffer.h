#pragma once
// Structural changes recorded during a phase, replayed in order when the phase ends.
#include <cstdint>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "engine/ecs/component_pool.h"
#include "engine/ecs/entity.h"

namespace rtrt::ecs {

enum class CommandOp : uint8_t { kCreate, kDestroy, kAdd, kRemove };

struct Command {
    CommandOp op;
    uint32_t typeId;   // component type, for kAdd and kRemove
    uint32_t payload;  // index into the type's payload list, for kAdd
    Entity entity;
};

// The registry records here while it defers; it decides at replay what still applies (a command
// on an entity destroyed earlier in the buffer is dropped). Added components wait in one typed
// list per component type, so recording allocates nothing per command once the lists have grown.
class CommandBuffer {
  public:
    void Create(Entity reserved) { commands_.push_back({CommandOp::kCreate, 0, 0, reserved}); }
    void Destroy(Entity e) { commands_.push_back({CommandOp::kDestroy, 0, 0, e}); }

    template <typename T>
    void Add(Entity e, T component) {
        const uint32_t typeId = ComponentTypeId<T>();
        std::vector<T>& payloads = Payloads<T>(typeId);
        commands_.push_back({CommandOp::kAdd, typeId, static_cast<uint32_t>(payloads.size()), e});
        payloads.push_back(std::move(component));
    }

    template <typename T>
    void Remove(Entity e) {
        commands_.push_back({CommandOp::kRemove, ComponentTypeId<T>(), 0, e});
    }

    std::span<const Command> Commands() const { return commands_; }
    bool Empty() const { return commands_.empty(); }

    // Moves the component of a kAdd command into pool, which must be the pool of its type.
    void AddInto(const Command& add, PoolBase& pool) {
        payloads_[add.typeId]->AddInto(pool, add.entity, add.payload);
    }

    // Keeps the lists' capacity for the next phase.
    void Clear() {
        commands_.clear();
        for (const auto& list : payloads_) {
            if (list) list->Clear();
        }
    }

  private:
    struct PayloadListBase {
        virtual ~PayloadListBase() = default;
        virtual void AddInto(PoolBase& pool, Entity e, uint32_t index) = 0;
        virtual void Clear() = 0;
    };
    template <typename T>
    struct PayloadList final : PayloadListBase {
        void AddInto(PoolBase& pool, Entity e, uint32_t index) override {
            static_cast<ComponentPool<T>&>(pool).Add(e, std::move(items[index]));
        }
        void Clear() override { items.clear(); }
        std::vector<T> items;
    };

    template <typename T>
    std::vector<T>& Payloads(uint32_t typeId) {
        if (typeId >= payloads_.size()) payloads_.resize(typeId + 1);
        if (!payloads_[typeId]) payloads_[typeId] = std::make_unique<PayloadList<T>>();
        return static_cast<PayloadList<T>&>(*payloads_[typeId]).items;
    }

    std::vector<Command> commands_;
    std::vector<std::unique_ptr<PayloadListBase>> payloads_;  // by component type id
};

}  // namespace rtrt::ecs

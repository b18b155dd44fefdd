#include "engine/ecs/registry.h"

namespace rtrt::ecs {

Entity Registry::Create() {
    if (!Deferring()) return entities_.Create();
    const Entity e = entities_.Reserve();
    commands_.Create(e);
    return e;
}

bool Registry::Destroy(Entity e) {
    if (!Deferring()) return DestroyNow(e);
    if (!Known(e)) return false;
    commands_.Destroy(e);
    return true;
}

void Registry::EndDeferred() {
    if (deferDepth_ == 0) return;
    if (--deferDepth_ == 0) Flush();
}

bool Registry::DestroyNow(Entity e) {
    if (!Valid(e)) return false;
    for (const auto& pool : pools_) {
        if (pool) pool->Remove(e);
    }
    return entities_.Destroy(e);
}

void Registry::Flush() {
    for (const Command& command : commands_.Commands()) {
        switch (command.op) {
            case CommandOp::kCreate:
                entities_.Activate(command.entity);
                break;
            case CommandOp::kDestroy:
                DestroyNow(command.entity);
                break;
            case CommandOp::kAdd:
                if (Valid(command.entity)) commands_.AddInto(command, *pools_[command.typeId]);
                break;
            case CommandOp::kRemove:
                pools_[command.typeId]->Remove(command.entity);
                break;
        }
    }
    commands_.Clear();
}

}  // namespace rtrt::ecs

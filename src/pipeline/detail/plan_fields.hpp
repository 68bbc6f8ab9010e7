#pragma once
// The field lists of plan_codec.cpp, declared for the encode/decode templates (JSON values and
// bytes).
#include "pipeline/cache_status.hpp"
#include "pipeline/detail/plan_binary.hpp"
#include "pipeline/detail/plan_codec.hpp"
#include "pipeline/plan.hpp"

namespace tw::detail {

TW_PLAN_FIELDS(Vec2);
TW_PLAN_FIELDS(TileSpec);
TW_PLAN_FIELDS(LineFeature);
TW_PLAN_FIELDS(Curve);
TW_PLAN_FIELDS(Piece);
TW_PLAN_FIELDS(Ribbon);
TW_PLAN_FIELDS(RoadProfile);
TW_PLAN_FIELDS(RiverProfile);
TW_PLAN_FIELDS(RidgeProfile);
TW_PLAN_FIELDS(TerrainFeature);
TW_PLAN_FIELDS(TerrainParams);
TW_PLAN_FIELDS(ProfileLimit);
TW_PLAN_FIELDS(FeatureEarthwork);
TW_PLAN_FIELDS(TerrainPlan);
TW_PLAN_FIELDS(GeneratedTerrain);
TW_PLAN_FIELDS(HeightfieldOptions);
TW_PLAN_FIELDS(HeightfieldFile);
TW_PLAN_FIELDS(RenderOptions);
TW_PLAN_FIELDS(WindowIndex);
TW_PLAN_FIELDS(AvoidanceInputs);
TW_PLAN_FIELDS(Warning);
TW_PLAN_FIELDS(StageTiming);
TW_PLAN_FIELDS(CacheStatus);
TW_PLAN_FIELDS(FeatureReport);
TW_PLAN_FIELDS(FeatureClassReport);
TW_PLAN_FIELDS(RunReport);

}  // namespace tw::detail

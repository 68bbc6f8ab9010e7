#include "pipeline/schema.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

#include "pipeline/detail/pipeline_keys.hpp"

namespace tw {

namespace {

using detail::KeyBlock;
using detail::KeyDefault;
using detail::KeySpec;
using detail::ValueForm;
using detail::ValueType;
using json = nlohmann::ordered_json;

json reference(std::string_view block) {
  return {{"$ref", "#/definitions/" + std::string(block)}};
}

// minimum / exclusiveMinimum / maximum / exclusiveMaximum of a number or integer form.
void add_range(json& out, const ValueForm& form) {
  const auto value = [&](double v) {
    return form.type == ValueType::integer ? json(std::int64_t(v)) : json(v);
  };
  if (std::isfinite(form.minimum))
    out[form.exclusive_minimum ? "exclusiveMinimum" : "minimum"] = value(form.minimum);
  if (std::isfinite(form.maximum))
    out[form.exclusive_maximum ? "exclusiveMaximum" : "maximum"] = value(form.maximum);
}

json string_choice(const std::vector<std::string_view>& values) {
  json out = {{"type", "string"}, {"enum", json::array()}};
  for (std::string_view v : values) out["enum"].push_back(v);
  return out;
}

json fragment(const ValueForm& form) {
  switch (form.type) {
    case ValueType::null_value:
      return {{"type", "null"}};
    case ValueType::number:
    case ValueType::integer: {
      json out = {{"type", form.type == ValueType::integer ? "integer" : "number"}};
      add_range(out, form);
      return out;
    }
    case ValueType::boolean:
      return {{"type", "boolean"}};
    case ValueType::string:
      return {{"type", "string"}};
    case ValueType::path:
      return {{"type", "string"}, {"minLength", 1}};
    case ValueType::choice:
      return string_choice(form.values);
    case ValueType::choice_list:
      return {{"type", "array"}, {"items", string_choice(form.values)}, {"uniqueItems", true}};
    case ValueType::string_list:
      return {{"type", "array"}, {"items", {{"type", "string"}}}};
    case ValueType::path_list:
      return {
          {"type", "array"}, {"items", {{"type", "string"}, {"minLength", 1}}}, {"minItems", 1}};
    case ValueType::number_list:
      return {{"type", "array"},
              {"items", {{"type", "number"}}},
              {"minItems", form.count},
              {"maxItems", form.count}};
    case ValueType::block:
      return reference(form.block);
    case ValueType::block_list: {
      json out = {{"type", "array"}, {"items", reference(form.block)}};
      if (form.count > 0) out["minItems"] = form.count;
      return out;
    }
    case ValueType::map_string:
      return {{"type", "object"},
              {"minProperties", 1},
              {"additionalProperties", {{"type", "string"}, {"minLength", 1}}}};
    case ValueType::map_number: {
      json number = {{"type", "number"}};
      add_range(number, form);
      return {{"type", "object"}, {"minProperties", 1}, {"additionalProperties", number}};
    }
    case ValueType::tags: {
      // A tag value is any scalar (`lanes: 2` selects "2").
      const json scalar = {{"type", json::array({"string", "number", "boolean"})}};
      return {{"type", "object"},
              {"minProperties", 1},
              {"propertyNames", {{"minLength", 1}}},
              {"additionalProperties",
               {{"anyOf",
                 json::array({scalar, {{"type", "array"}, {"items", scalar}, {"minItems", 1}}})}}}};
    }
    case ValueType::channels:
      return {{"type", "object"},
              {"minProperties", 1},
              {"additionalProperties", {{"type", "string"}, {"pattern", "^(height|splat\\..+)$"}}}};
    case ValueType::feature_classes:
      // `kind: area` decides which reader takes the class (MethodReader::takes_class).
      return {{"type", "object"},
              {"minProperties", 1},
              {"propertyNames", {{"pattern", "^[A-Za-z_][A-Za-z0-9_-]*$"}}},
              {"additionalProperties",
               {{"if",
                 {{"type", "object"},
                  {"properties", {{"kind", {{"const", "area"}}}}},
                  {"required", json::array({"kind"})}}},
                {"then", reference("area_class")},
                {"else", reference("line_class")}}}};
  }
  return json::object();
}

json key_schema(const KeySpec& key) {
  json out;
  if (key.forms.size() == 1) {
    out = fragment(key.forms.front());
  } else {
    out["anyOf"] = json::array();
    for (const ValueForm& form : key.forms) out["anyOf"].push_back(fragment(form));
  }
  out["description"] = key.description;
  switch (key.fallback.kind) {
    case KeyDefault::Kind::none:
      break;
    case KeyDefault::Kind::number: {
      const double v = key.fallback.number;
      out["default"] = v == std::floor(v) && std::abs(v) < 1e15 ? json(std::int64_t(v)) : json(v);
      break;
    }
    case KeyDefault::Kind::boolean:
      out["default"] = key.fallback.boolean;
      break;
    case KeyDefault::Kind::text:
      out["default"] = key.fallback.text;
      break;
  }
  return out;
}

json block_schema(const KeyBlock& block) {
  json out = {{"type", "object"},
              {"description", block.description},
              {"properties", json::object()},
              {"additionalProperties", false}};
  json required = json::array();
  for (const KeySpec& key : block.keys) {
    out["properties"][std::string(key.name)] = key_schema(key);
    if (key.required) required.push_back(key.name);
  }
  if (!required.empty()) out["required"] = required;
  return out;
}

}  // namespace

std::string pipeline_schema_json() {
  json schema = {{"$schema", "http://json-schema.org/draft-07/schema#"},
                 {"title", "terraweave pipeline"}};
  json definitions = json::object();
  for (const KeyBlock& block : detail::pipeline_blocks()) {
    if (block.name == "root") {
      schema.update(block_schema(block));
    } else {
      definitions[std::string(block.name)] = block_schema(block);
    }
  }
  schema["definitions"] = definitions;
  return schema.dump(2) + "\n";
}

}  // namespace tw

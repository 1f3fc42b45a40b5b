#include "temporal/taa_ranks.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace kdop {
namespace {

using nlohmann::json;

json to_json(const FrameFigures& f) { return {{"sequence", f.sequence}, {"index", f.index}, {"values", f.values}}; }

json to_json(const EvaluationRow& row) {
    json frames = json::array();
    for (const FrameFigures& f : row.per_frame) frames.push_back(to_json(f));
    return {{"variant", row.variant},
            {"source", row.source},
            {"means", row.means},
            {"against_reference", row.against_reference},
            {"hdr", row.range == ColorRange::hdr},
            {"notes", row.notes},
            {"per_frame", std::move(frames)},
            {"upscale", row.upscale}};
}

json to_json(const ViewerSequence& s) {
    return {{"name", s.name},     {"scene", s.scene}, {"figure", s.figure},   {"hdr", s.range == ColorRange::hdr},
            {"truth", s.truth},   {"map", s.map},     {"width", s.width},     {"height", s.height},
            {"frames", s.frames}, {"worst", s.worst}, {"figures", s.figures}, {"variants", s.variants}};
}

json to_json(const MeasuredSource& source) {
    json rows = json::array(), viewed = json::array();
    for (const EvaluationRow& row : source.rows) rows.push_back(to_json(row));
    for (const ViewerSequence& s : source.viewed) viewed.push_back(to_json(s));
    return {{"rows", std::move(rows)}, {"picture", source.picture}, {"viewed", std::move(viewed)}};
}

ColorRange range_of(const json& j) { return j.at("hdr").get<bool>() ? ColorRange::hdr : ColorRange::ldr; }

MeasuredSource measured_from(const json& j) {
    MeasuredSource source;
    for (const json& r : j.at("rows")) {
        EvaluationRow& row = source.rows.emplace_back();
        row.variant = r.at("variant").get<std::size_t>();
        row.source = r.at("source").get<std::string>();
        row.means = r.at("means").get<std::vector<double>>();
        row.against_reference = r.at("against_reference").get<bool>();
        row.range = range_of(r);
        row.notes = r.at("notes").get<std::vector<std::string>>();
        row.upscale = r.at("upscale").get<double>();
        for (const json& f : r.at("per_frame"))
            row.per_frame.push_back({f.at("sequence").get<std::string>(), f.at("index").get<std::size_t>(),
                                     f.at("values").get<std::vector<double>>()});
    }
    source.picture = j.at("picture").get<std::string>();
    for (const json& v : j.at("viewed")) {
        ViewerSequence& s = source.viewed.emplace_back();
        s.name = v.at("name").get<std::string>();
        s.scene = v.at("scene").get<std::string>();
        s.figure = v.at("figure").get<std::size_t>();
        s.range = range_of(v);
        s.truth = v.at("truth").get<std::string>();
        s.map = v.at("map").get<std::string>();
        s.width = v.at("width").get<std::uint32_t>();
        s.height = v.at("height").get<std::uint32_t>();
        s.frames = v.at("frames").get<std::vector<std::size_t>>();
        s.worst = v.at("worst").get<std::vector<std::size_t>>();
        s.figures = v.at("figures").get<std::vector<std::vector<double>>>();
        s.variants = v.at("variants").get<std::size_t>();
    }
    return source;
}

std::string cbor(const json& j) {
    const std::vector<std::uint8_t> bytes = json::to_cbor(j);
    return {bytes.begin(), bytes.end()};
}

} // namespace

std::vector<int> source_owners(const Ranks& ranks, const TaaSources& sources, const TaaEvaluation& evaluation,
                               const TaaSchedule& schedule) {
    std::vector<double> costs;
    auto add = [&](const FrameSource& frames, std::size_t count) {
        costs.push_back(double(count) * frames.width() * frames.height() * double(evaluation.shader_count(frames)));
    };
    for (const auto& scene : sources.scenes) add(*ghosting_frames(*scene, schedule), evaluation.frames(*scene));
    for (const SequenceFrames& sequence : sources.sequences) add(sequence, sequence.frame_count());
    for (const NssFrames& capture : sources.captures) add(capture, capture.frame_count());
    return ranks.balance(costs);
}

std::size_t viewed_sequences(const TaaSources& sources, std::size_t i) { return i < sources.scenes.size() ? 2 : 1; }

std::string measured_source_bytes(const MeasuredSource& source) { return cbor(to_json(source)); }

Result<MeasuredSource> measured_source_from(const std::string& bytes) {
    try {
        return measured_from(json::from_cbor(bytes));
    } catch (const json::exception& e) {
        return fail(fmt::format("a rank's figures cannot be read: {}", e.what()));
    }
}

GatheredSources gather_sources(const Ranks& ranks, std::vector<std::optional<MeasuredSource>> mine,
                               const RunMetadata::RankShare& me, StagedImages& images) {
    GatheredSources gathered;
    if (ranks.size() == 1) {
        for (std::optional<MeasuredSource>& source : mine) gathered.sources.push_back(std::move(*source));
        gathered.shares = {me};
        return gathered;
    }
    // This rank's device, time, figures and staged images' names in one message (rank 0 keeps its own),
    // then each image's bytes.
    json message{{"device", me.device}, {"seconds", me.seconds}, {"files", images.names()}, {"sources", json::array()}};
    for (std::size_t i = 0; i < mine.size() && !ranks.is_root(); ++i)
        if (mine[i]) message["sources"].push_back({{"index", i}, {"source", to_json(*mine[i])}});
    const std::vector<std::string> all = ranks.gather_to_root(cbor(message));
    if (!ranks.is_root()) {
        for (const std::string& name : images.names()) {
            auto bytes = images.bytes(name);
            if (!bytes) ranks.abort(bytes.error().message);
            ranks.send(*bytes, 0);
        }
        return gathered;
    }
    std::vector<std::optional<MeasuredSource>> sources = std::move(mine);
    for (int r = 0; r < ranks.size(); ++r) {
        json received;
        try {
            received = json::from_cbor(all[std::size_t(r)]);
            gathered.shares.push_back(
                {received.at("device").get<std::string>(), received.at("seconds").get<double>(), {}});
            if (r > 0)
                for (const json& s : received.at("sources"))
                    sources.at(s.at("index").get<std::size_t>()) = measured_from(s.at("source"));
        } catch (const std::exception& e) {
            ranks.abort(fmt::format("rank {}'s figures cannot be read: {}", r, e.what()));
        }
        if (r == 0) continue;
        for (const json& name : received.at("files"))
            if (auto ok = images.add_encoded(name.get<std::string>(), ranks.receive(r)); !ok)
                ranks.abort(ok.error().message);
    }
    for (std::size_t i = 0; i < sources.size(); ++i) {
        if (!sources[i]) ranks.abort(fmt::format("source {} was measured by no rank", i));
        gathered.sources.push_back(std::move(*sources[i]));
    }
    return gathered;
}

} // namespace kdop

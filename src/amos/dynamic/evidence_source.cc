#include "amos/dynamic/evidence_source.h"

namespace amos::dynamic {

EvidenceSource::~EvidenceSource() = default;

bool EvidenceSource::appliesTo(const EvidenceContext& /*context*/) const { return true; }

}  // namespace amos::dynamic

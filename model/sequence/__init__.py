"""Lift sequences: turnover and upending at held angles, hooks moved with the body on its
elastic ropes, the worst load found between the steps.

``load_sequence(path)`` reads a sequence file; ``run_sequence(sequence)`` sweeps its stages
(:mod:`liftplan.model.sequence.sweep`).
"""

from liftplan.model.sequence.file import load_sequence, loads_sequence
from liftplan.model.sequence.objects import Sequence, Stage, crane_key
from liftplan.model.sequence.statics import HeldAngle, pose_matrix
from liftplan.model.sequence.sweep import SequenceResult, StageResult, run_sequence

__all__ = [
    "HeldAngle",
    "Sequence",
    "SequenceResult",
    "Stage",
    "StageResult",
    "crane_key",
    "load_sequence",
    "loads_sequence",
    "pose_matrix",
    "run_sequence",
]

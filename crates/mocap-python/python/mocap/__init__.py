"""Motion capture for Python: the mocap core's readers, forward kinematics,
edits, retargeting and writers, with NumPy arrays out.

>>> import mocap
>>> clip = mocap.read("walk.bvh")
>>> clip.world_positions().shape        # frames x joints (End Sites included) x 3
"""

from ._mocap import Clip, ParseError, from_arrays, read, read_many
from ._batch import batch, summarise
from ._mocap import motion_files

__all__ = ["Clip", "ParseError", "batch", "from_arrays", "motion_files", "read", "read_many", "summarise"]

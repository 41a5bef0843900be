"""Links, joints, sliders and mobility: the mechanism a scene describes."""

from kinepoly.model.mechanism import Joint, Mechanism, Revolute, build_mechanism

__all__ = ["Joint", "Mechanism", "Revolute", "build_mechanism"]

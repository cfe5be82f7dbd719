"""Involute spur gear geometry, pure numpy: the involute (:mod:`.involute`), biarc fitting (:mod:`.fit`), exact
offsets of arc contours (:mod:`.offset`), a tooth cut by the basic rack (:mod:`.tooth`), whole outlines
(:mod:`.outline`) and meshing pairs with the designer's checks (:mod:`.pair`). Lengths mm, angles rad."""

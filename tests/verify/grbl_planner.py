"""GRBL 1.1's planner as published, transcribed: the reference for camcam.verify.motion_time.

Source: gnea/grbl at bfb67f0 (the search tool's mirror of github:gnea/grbl), files and functions cited at
each step.  What is transcribed:

* ``motion_control.c`` ``mc_arc``: an arc cut into chords, ``segments = floor(|½ · travel · r| /
  sqrt(tol · (2r − tol)))`` with ``$12`` arc tolerance 0.002 mm (``defaults.h``), the radius vector turned
  by the third-order small-angle rotation and corrected exactly every ``N_ARC_CORRECTION`` = 12 chords
  (``config.h``), the last chord to the arc's printed end.
* ``planner.c`` ``plan_buffer_line``: targets rounded to steps (``lround(target · steps_per_mm)``,
  250 steps/mm, ``defaults.h`` DEFAULTS_GENERIC), the block's ``millimeters`` and unit vector
  (``nuts_bolts.c`` ``convert_delta_vector_to_unit_vector``), its acceleration and rapid rate limited by
  the axes (``limit_value_by_axis_maximum``), the junction speed from ``junction_cos_theta``,
  ``junction_unit_vec`` and the junction deviation, ``plan_compute_profile_nominal_speed`` (no overrides:
  100 %) and ``plan_compute_profile_parameters``.
* ``planner.c`` ``planner_recalculate``: the reverse pass from the newest block (planned to a stop) back
  to ``block_buffer_planned``, the forward pass moving ``block_buffer_planned``, over a ring buffer of
  ``BLOCK_BUFFER_SIZE`` = 16 (``planner.h``; the head slot is always empty: 15 blocks of look-ahead).
* ``motion_control.c`` ``mc_line``: a new block waits while ``plan_check_full_buffer()``: the stepper
  runs the tail block and ``plan_discard_current_block`` frees it.  This model streams as GRBL does when
  the sender keeps the buffer full: the tail runs when a new block needs its slot, with the plan of that
  moment, its exit speed ``plan_get_exec_block_exit_speed_sqr()``.
* ``stepper.c`` ``st_prep_buffer``: the tail block's profile (acceleration ramp to ``accelerate_until``,
  cruise, deceleration from ``decelerate_after``; trapezoid, triangle, acceleration- or
  deceleration-only), timed here in closed form instead of in 1/``ACCELERATION_TICKS_PER_SECOND`` segments.

Not transcribed: feed/rapid overrides, system motions, float32 arithmetic (float64 here), COREXY.  GRBL 1.1
has three axes; a move that turns A is refused.  Units: mm and seconds (GRBL keeps mm/min and mm/min²;
the equations are homogeneous).
"""

from __future__ import annotations

import math
import re

BLOCK_BUFFER_SIZE = 16  # planner.h (without USE_LINE_NUMBERS)
N_ARC_CORRECTION = 12  # config.h
ARC_ANGULAR_TRAVEL_EPSILON = 5e-7  # config.h, radians
MINIMUM_JUNCTION_SPEED = 0.0  # config.h (mm/min)
MINIMUM_FEED_RATE = 1.0 / 60.0  # config.h: 1.0 mm/min, here mm/s
SOME_LARGE_VALUE = 1.0e38  # nuts_bolts.h
STEPS_PER_MM = 250.0  # defaults.h DEFAULTS_GENERIC $100-$102
ARC_TOLERANCE_MM = 0.002  # defaults.h DEFAULT_ARC_TOLERANCE ($12)
N_AXIS = 3


def lround(x: float) -> int:
    """C's lround: halves away from zero."""
    return int(math.floor(abs(x) + 0.5)) * (1 if x >= 0 else -1)


def limit_value_by_axis_maximum(max_value, unit_vec) -> float:
    """nuts_bolts.c: the largest value along ``unit_vec`` no axis's ``max_value`` is exceeded by."""
    limit = SOME_LARGE_VALUE
    for m, u in zip(max_value, unit_vec):
        if u != 0:
            limit = min(limit, abs(m / u))
    return limit


class Block:
    __slots__ = ("millimeters", "acceleration", "rapid_rate", "programmed_rate", "entry_speed_sqr",
                 "max_entry_speed_sqr", "max_junction_speed_sqr", "rapid")


class GrblPlanner:
    """GRBL's planner, ring buffer and block executor; :meth:`line` and :meth:`arc` take program moves,
    ``elapsed_s`` accumulates the executed blocks' times."""

    def __init__(self, *, acceleration_mm_s2: float, max_rate_mm_s: float, junction_deviation_mm: float):
        self.acceleration = [acceleration_mm_s2] * N_AXIS  # $120-$122
        self.max_rate = [max_rate_mm_s] * N_AXIS  # $110-$112
        self.junction_deviation = junction_deviation_mm  # $11
        self.buffer = [None] * BLOCK_BUFFER_SIZE
        self.tail = self.head = self.planned = 0  # plan_reset_buffer
        self.next_head = 1
        self.position_steps = [0] * N_AXIS  # pl.position
        self.previous_unit_vec = [0.0] * N_AXIS
        self.previous_nominal_speed = 0.0
        self.elapsed_s = 0.0
        self.blocks_run = 0

    # -- ring buffer (planner.c) -----------------------------------------------------------------------
    @staticmethod
    def next_index(i):
        return 0 if i + 1 == BLOCK_BUFFER_SIZE else i + 1

    @staticmethod
    def prev_index(i):
        return BLOCK_BUFFER_SIZE - 1 if i == 0 else i - 1

    def full(self) -> bool:  # plan_check_full_buffer
        return self.tail == self.next_head

    def exec_block_exit_speed_sqr(self) -> float:  # plan_get_exec_block_exit_speed_sqr
        i = self.next_index(self.tail)
        return 0.0 if i == self.head else self.buffer[i].entry_speed_sqr

    def discard_current_block(self):  # plan_discard_current_block
        if self.head != self.tail:
            i = self.next_index(self.tail)
            if self.tail == self.planned:
                self.planned = i
            self.tail = i

    # -- the executor (stepper.c st_prep_buffer's profile, timed) ----------------------------------------
    def run_tail(self):
        b = self.buffer[self.tail]
        a = b.acceleration
        inv_2_accel = 0.5 / a
        exit_speed_sqr = self.exec_block_exit_speed_sqr()
        nominal_speed = self.nominal_speed(b)
        nominal_speed_sqr = nominal_speed * nominal_speed
        mm = b.millimeters
        accelerate_until, decelerate_after = mm, 0.0  # distances left in the block (stepper.c)
        entry = math.sqrt(b.entry_speed_sqr)
        exit_ = math.sqrt(exit_speed_sqr)
        maximum = nominal_speed
        intersect_distance = 0.5 * (mm + inv_2_accel * (b.entry_speed_sqr - exit_speed_sqr))
        if b.entry_speed_sqr > nominal_speed_sqr:
            raise AssertionError("entry above nominal happens only with overrides (not modelled)")
        if intersect_distance > 0.0:
            if intersect_distance < mm:  # trapezoid or triangle
                decelerate_after = inv_2_accel * (nominal_speed_sqr - exit_speed_sqr)
                if decelerate_after < intersect_distance:  # trapezoid
                    if b.entry_speed_sqr != nominal_speed_sqr:
                        accelerate_until -= inv_2_accel * (nominal_speed_sqr - b.entry_speed_sqr)
                else:  # triangle
                    accelerate_until = decelerate_after = intersect_distance
                    maximum = math.sqrt(2.0 * a * intersect_distance + exit_speed_sqr)
            else:  # deceleration only
                accelerate_until, decelerate_after, maximum = mm, mm, entry
        else:  # acceleration only
            accelerate_until, decelerate_after, maximum = 0.0, 0.0, exit_
        t = (maximum - entry) / a + (maximum - exit_) / a
        cruise = accelerate_until - decelerate_after
        if cruise > 0.0:
            t += cruise / maximum
        self.elapsed_s += t
        self.blocks_run += 1
        self.discard_current_block()

    def finish(self):
        """Run what is left in the buffer (the program's end: the last block stops)."""
        while self.head != self.tail:
            self.run_tail()

    # -- planner.c ------------------------------------------------------------------------------------------
    @staticmethod
    def nominal_speed(b) -> float:  # plan_compute_profile_nominal_speed, overrides at 100 %
        v = b.programmed_rate
        if not b.rapid and v > b.rapid_rate:
            v = b.rapid_rate
        return v if v > MINIMUM_FEED_RATE else MINIMUM_FEED_RATE

    @staticmethod
    def compute_profile_parameters(b, nominal_speed, prev_nominal_speed):  # plan_compute_profile_parameters
        v = prev_nominal_speed if nominal_speed > prev_nominal_speed else nominal_speed
        b.max_entry_speed_sqr = v * v  # as GRBL multiplies (Python's ** 2 may round differently)
        if b.max_entry_speed_sqr > b.max_junction_speed_sqr:
            b.max_entry_speed_sqr = b.max_junction_speed_sqr

    def buffer_line(self, target, feed_mm_s: float | None):
        """plan_buffer_line; ``feed_mm_s`` None: a rapid (G0)."""
        while self.full():  # mc_line waits for the stepper
            self.run_tail()
        b = Block()
        b.rapid = feed_mm_s is None
        target_steps = [lround(t * STEPS_PER_MM) for t in target]
        unit_vec = [(target_steps[i] - self.position_steps[i]) / STEPS_PER_MM for i in range(N_AXIS)]
        if all(s == p for s, p in zip(target_steps, self.position_steps)):
            return  # PLAN_EMPTY_BLOCK
        magnitude = math.sqrt(sum(u * u for u in unit_vec if u != 0.0))
        unit_vec = [u / magnitude for u in unit_vec]
        b.millimeters = magnitude
        b.acceleration = limit_value_by_axis_maximum(self.acceleration, unit_vec)
        b.rapid_rate = limit_value_by_axis_maximum(self.max_rate, unit_vec)
        b.programmed_rate = b.rapid_rate if b.rapid else feed_mm_s
        if self.head == self.tail:
            b.entry_speed_sqr = 0.0
            b.max_junction_speed_sqr = 0.0
        else:
            junction_cos_theta = -sum(p * u for p, u in zip(self.previous_unit_vec, unit_vec))
            junction_unit_vec = [u - p for p, u in zip(self.previous_unit_vec, unit_vec)]
            if junction_cos_theta > 0.999999:
                b.max_junction_speed_sqr = MINIMUM_JUNCTION_SPEED ** 2
            elif junction_cos_theta < -0.999999:
                b.max_junction_speed_sqr = SOME_LARGE_VALUE
            else:
                m = math.sqrt(sum(j * j for j in junction_unit_vec if j != 0.0))
                junction_unit_vec = [j / m for j in junction_unit_vec]
                junction_acceleration = limit_value_by_axis_maximum(self.acceleration, junction_unit_vec)
                sin_theta_d2 = math.sqrt(0.5 * (1.0 - junction_cos_theta))
                b.max_junction_speed_sqr = max(MINIMUM_JUNCTION_SPEED ** 2, (junction_acceleration * self.junction_deviation
                                                                              * sin_theta_d2) / (1.0 - sin_theta_d2))
            b.entry_speed_sqr = 0.0
        nominal_speed = self.nominal_speed(b)
        self.compute_profile_parameters(b, nominal_speed, self.previous_nominal_speed)
        self.previous_nominal_speed = nominal_speed
        self.previous_unit_vec = unit_vec
        self.position_steps = target_steps
        self.buffer[self.head] = b
        self.head = self.next_head
        self.next_head = self.next_index(self.head)
        self.recalculate()

    def recalculate(self):  # planner_recalculate
        block_index = self.prev_index(self.head)
        if block_index == self.planned:
            return
        current = self.buffer[block_index]
        current.entry_speed_sqr = min(current.max_entry_speed_sqr, 2 * current.acceleration * current.millimeters)
        block_index = self.prev_index(block_index)
        if block_index != self.planned:
            while block_index != self.planned:
                nxt = current
                current = self.buffer[block_index]
                block_index = self.prev_index(block_index)
                if current.entry_speed_sqr != current.max_entry_speed_sqr:
                    entry_speed_sqr = nxt.entry_speed_sqr + 2 * current.acceleration * current.millimeters
                    current.entry_speed_sqr = min(entry_speed_sqr, current.max_entry_speed_sqr)
        nxt = self.buffer[self.planned]
        block_index = self.next_index(self.planned)
        while block_index != self.head:
            current = nxt
            nxt = self.buffer[block_index]
            if current.entry_speed_sqr < nxt.entry_speed_sqr:
                entry_speed_sqr = current.entry_speed_sqr + 2 * current.acceleration * current.millimeters
                if entry_speed_sqr < nxt.entry_speed_sqr:
                    nxt.entry_speed_sqr = entry_speed_sqr
                    self.planned = block_index
            if nxt.entry_speed_sqr == nxt.max_entry_speed_sqr:
                self.planned = block_index
            block_index = self.next_index(block_index)

    # -- motion_control.c ---------------------------------------------------------------------------------
    def arc(self, position, target, offset, feed_mm_s: float, clockwise: bool):
        """mc_arc in the XY plane (axis_linear Z); ``offset`` is I J from ``position``."""
        position = list(position)
        radius = math.hypot(offset[0], offset[1])  # gcode.c: the radius of the IJ offset
        center_axis0 = position[0] + offset[0]
        center_axis1 = position[1] + offset[1]
        r_axis0, r_axis1 = -offset[0], -offset[1]
        rt_axis0, rt_axis1 = target[0] - center_axis0, target[1] - center_axis1
        angular_travel = math.atan2(r_axis0 * rt_axis1 - r_axis1 * rt_axis0, r_axis0 * rt_axis0 + r_axis1 * rt_axis1)
        if clockwise:
            if angular_travel >= -ARC_ANGULAR_TRAVEL_EPSILON:
                angular_travel -= 2 * math.pi
        elif angular_travel <= ARC_ANGULAR_TRAVEL_EPSILON:
            angular_travel += 2 * math.pi
        segments = math.floor(abs(0.5 * angular_travel * radius)
                              / math.sqrt(ARC_TOLERANCE_MM * (2 * radius - ARC_TOLERANCE_MM)))
        if segments:
            theta_per_segment = angular_travel / segments
            linear_per_segment = (target[2] - position[2]) / segments
            cos_t = 2.0 - theta_per_segment * theta_per_segment
            sin_t = theta_per_segment * 0.16666667 * (cos_t + 4.0)
            cos_t *= 0.5
            count = 0
            for i in range(1, segments):
                if count < N_ARC_CORRECTION:
                    r_axisi = r_axis0 * sin_t + r_axis1 * cos_t
                    r_axis0 = r_axis0 * cos_t - r_axis1 * sin_t
                    r_axis1 = r_axisi
                    count += 1
                else:
                    cos_ti, sin_ti = math.cos(i * theta_per_segment), math.sin(i * theta_per_segment)
                    r_axis0 = -offset[0] * cos_ti + offset[1] * sin_ti
                    r_axis1 = -offset[0] * sin_ti - offset[1] * cos_ti
                    count = 0
                position[0] = center_axis0 + r_axis0
                position[1] = center_axis1 + r_axis1
                position[2] += linear_per_segment
                self.buffer_line(position, feed_mm_s)
        self.buffer_line(target, feed_mm_s)


def grbl_time_s(printed_moves, *, acceleration_mm_s2: float, rapid_mm_min: float, junction_deviation_mm: float) -> float:
    """Seconds GRBL's planner and executor take over ``printed_moves`` (``Program.printed_moves`` of a 3-axis
    program), streamed with a full buffer; tool changes add their seconds (GRBL has none)."""
    grbl = GrblPlanner(acceleration_mm_s2=acceleration_mm_s2, max_rate_mm_s=rapid_mm_min / 60.0,
                       junction_deviation_mm=junction_deviation_mm)
    extra = 0.0
    for move in printed_moves:
        kind = move[0]
        if kind == "comment":
            continue
        if kind == "tool change":
            grbl.finish()
            extra += move[1]
        elif kind == "rapid":
            grbl.buffer_line(move[2], None)
        elif kind == "line":
            if move[4] != move[5]:
                raise ValueError("GRBL 1.1 has no A axis")
            grbl.buffer_line(move[2], move[3] / 60.0)
        elif kind == "arc":
            start, end, centre, ccw, feed = move[1:]
            grbl.arc(start, end, (centre[0] - start[0], centre[1] - start[1]), feed / 60.0, not ccw)
        else:
            raise ValueError(f"{kind} moves are not in GRBL 1.1's three axes")
    grbl.finish()
    return grbl.elapsed_s + extra


_WORD = re.compile(r"([A-Z])([-+]?[0-9]*\.?[0-9]*)")


def grbl_time_of_text_s(text: str, *, acceleration_mm_s2: float, rapid_mm_min: float,
                        junction_deviation_mm: float) -> float:
    """Seconds GRBL takes over a program's text: what ``gcode.c`` reads of camcam's GRBL programs (modal G0 G1
    G2 G3 and F, G90 absolute X Y Z, G91.1 incremental I J, G17, G21; comments in parentheses; S and M
    words move nothing), straight into the planner: independent of the writer's ``printed_moves``."""
    grbl = GrblPlanner(acceleration_mm_s2=acceleration_mm_s2, max_rate_mm_s=rapid_mm_min / 60.0,
                       junction_deviation_mm=junction_deviation_mm)
    position, motion, feed = [0.0, 0.0, 0.0], None, None
    for raw in text.splitlines():
        line = re.sub(r"\(.*?\)", "", raw).strip().upper()
        words = {}
        for letter, number in _WORD.findall(line):
            if letter == "G":
                g = float(number)
                if g in (0, 1, 2, 3):
                    motion = int(g)
                elif g == 93:
                    raise ValueError("inverse time (G93): not in this reference")
            else:
                words[letter] = float(number)
        if "F" in words:
            feed = words["F"] / 60.0
        if not any(axis in words for axis in "XYZ"):
            continue
        target = [words.get(axis, position[i]) for i, axis in enumerate("XYZ")]
        if motion == 0:
            grbl.buffer_line(target, None)
        elif motion == 1:
            grbl.buffer_line(target, feed)
        else:
            grbl.arc(position, target, (words.get("I", 0.0), words.get("J", 0.0)), feed, motion == 2)
        position = target
    grbl.finish()
    return grbl.elapsed_s

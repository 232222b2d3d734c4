"""Every model's kernels behind one signature, selected by the model index (sorted names).

GENERATED FILE: DO NOT EDIT.
Source: derive/codegen/dispatch.py (from the model table)
Regenerate with: lgekf derive      (check freshness with: lgekf derive --check)
"""
import numba as nb
import numpy as np

from . import ctrv, cv, se2r2, se2r3, se2se2

MODEL_NAMES = ('ctrv', 'cv', 'se2r2', 'se2r3', 'se2se2')
N_TANGENT = np.array([5, 4, 5, 6, 6])
N_INTERNAL = np.array([5, 4, 6, 7, 9])
#: COMMON_MISSING[model, k] = 1.0 where the model carries no information on common coordinate k (common_missing)
COMMON_MISSING = np.array([[0.0, 0.0, 0.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 0.0, 0.0, 1.0], [0.0, 0.0, 0.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 0.0, 0.0, 0.0]])


@nb.njit(cache=True, inline="always")
def predict(model, s, p, dt, q):
    if model == 0:
        ctrv.predict(s, p, dt, q[0], q[1])
    elif model == 1:
        cv.predict(s, p, dt, q[0])
    elif model == 2:
        se2r2.predict(s, p, dt, q[0], q[1])
    elif model == 3:
        se2r3.predict(s, p, dt, q[0], q[1], q[2])
    elif model == 4:
        se2se2.predict(s, p, dt, q[0], q[1], q[2])


@nb.njit(cache=True, inline="always")
def update_pose(model, s, p, z, r):
    if model == 0:
        return ctrv.update_pose(s, p, z[0], z[1], z[2], r[0], r[1], r[2])
    elif model == 2:
        return se2r2.update_pose(s, p, z[0], z[1], z[2], r[0], r[1], r[2])
    elif model == 3:
        return se2r3.update_pose(s, p, z[0], z[1], z[2], r[0], r[1], r[2])
    elif model == 4:
        return se2se2.update_pose(s, p, z[0], z[1], z[2], r[0], r[1], r[2])
    raise ValueError('dispatch: model index out of range')


@nb.njit(cache=True, inline="always")
def calH_pose(model, s):
    if model == 0:
        return ctrv.calH_pose(s)
    elif model == 2:
        return se2r2.calH_pose(s)
    elif model == 3:
        return se2r3.calH_pose(s)
    elif model == 4:
        return se2se2.calH_pose(s)
    raise ValueError('dispatch: model index out of range')


@nb.njit(cache=True, inline="always")
def innovation_logdet_pose(model, s, p, r):
    if model == 0:
        return ctrv.innovation_logdet_pose(s, p, r[0], r[1], r[2])
    elif model == 2:
        return se2r2.innovation_logdet_pose(s, p, r[0], r[1], r[2])
    elif model == 3:
        return se2r3.innovation_logdet_pose(s, p, r[0], r[1], r[2])
    elif model == 4:
        return se2se2.innovation_logdet_pose(s, p, r[0], r[1], r[2])
    raise ValueError('dispatch: model index out of range')


@nb.njit(cache=True, inline="always")
def update_position(model, s, p, z, r):
    if model == 0:
        return ctrv.update_position(s, p, z[0], z[1], r[0])
    elif model == 1:
        return cv.update_position(s, p, z[0], z[1], r[0])
    elif model == 2:
        return se2r2.update_position(s, p, z[0], z[1], r[0])
    elif model == 3:
        return se2r3.update_position(s, p, z[0], z[1], r[0])
    elif model == 4:
        return se2se2.update_position(s, p, z[0], z[1], r[0])
    raise ValueError('dispatch: model index out of range')


@nb.njit(cache=True, inline="always")
def calH_position(model, s):
    if model == 0:
        return ctrv.calH_position(s)
    elif model == 1:
        return cv.calH_position(s)
    elif model == 2:
        return se2r2.calH_position(s)
    elif model == 3:
        return se2r3.calH_position(s)
    elif model == 4:
        return se2se2.calH_position(s)
    raise ValueError('dispatch: model index out of range')


@nb.njit(cache=True, inline="always")
def innovation_logdet_position(model, s, p, r):
    if model == 0:
        return ctrv.innovation_logdet_position(s, p, r[0])
    elif model == 1:
        return cv.innovation_logdet_position(s, p, r[0])
    elif model == 2:
        return se2r2.innovation_logdet_position(s, p, r[0])
    elif model == 3:
        return se2r3.innovation_logdet_position(s, p, r[0])
    elif model == 4:
        return se2se2.innovation_logdet_position(s, p, r[0])
    raise ValueError('dispatch: model index out of range')


@nb.njit(cache=True, inline="always")
def state_from_physical(model, x):
    if model == 0:
        return ctrv.state_from_physical(x)
    elif model == 1:
        return cv.state_from_physical(x)
    elif model == 2:
        return se2r2.state_from_physical(x)
    elif model == 3:
        return se2r3.state_from_physical(x)
    elif model == 4:
        return se2se2.state_from_physical(x)
    raise ValueError('dispatch: model index out of range')


@nb.njit(cache=True, inline="always")
def state_to_physical(model, s):
    if model == 0:
        return ctrv.state_to_physical(s)
    elif model == 1:
        return cv.state_to_physical(s)
    elif model == 2:
        return se2r2.state_to_physical(s)
    elif model == 3:
        return se2r3.state_to_physical(s)
    elif model == 4:
        return se2se2.state_to_physical(s)
    raise ValueError('dispatch: model index out of range')


@nb.njit(cache=True, inline="always")
def physical_to_common(model, x):
    if model == 0:
        return ctrv.physical_to_common(x)
    elif model == 1:
        return cv.physical_to_common(x)
    elif model == 2:
        return se2r2.physical_to_common(x)
    elif model == 3:
        return se2r3.physical_to_common(x)
    elif model == 4:
        return se2se2.physical_to_common(x)
    raise ValueError('dispatch: model index out of range')


@nb.njit(cache=True, inline="always")
def physical_to_common_jacobian(model, x):
    if model == 0:
        return ctrv.physical_to_common_jacobian(x)
    elif model == 1:
        return cv.physical_to_common_jacobian(x)
    elif model == 2:
        return se2r2.physical_to_common_jacobian(x)
    elif model == 3:
        return se2r3.physical_to_common_jacobian(x)
    elif model == 4:
        return se2se2.physical_to_common_jacobian(x)
    raise ValueError('dispatch: model index out of range')


@nb.njit(cache=True, inline="always")
def common_to_state(model, c):
    if model == 0:
        return ctrv.common_to_state(c)
    elif model == 1:
        return cv.common_to_state(c)
    elif model == 2:
        return se2r2.common_to_state(c)
    elif model == 3:
        return se2r3.common_to_state(c)
    elif model == 4:
        return se2se2.common_to_state(c)
    raise ValueError('dispatch: model index out of range')


@nb.njit(cache=True, inline="always")
def common_jacobian(model, c):
    if model == 0:
        return ctrv.common_jacobian(c)
    elif model == 1:
        return cv.common_jacobian(c)
    elif model == 2:
        return se2r2.common_jacobian(c)
    elif model == 3:
        return se2r3.common_jacobian(c)
    elif model == 4:
        return se2se2.common_jacobian(c)
    raise ValueError('dispatch: model index out of range')


@nb.njit(cache=True, inline="always")
def common_missing(model):
    if model == 0:
        return ctrv.common_missing()
    elif model == 1:
        return cv.common_missing()
    elif model == 2:
        return se2r2.common_missing()
    elif model == 3:
        return se2r3.common_missing()
    elif model == 4:
        return se2se2.common_missing()
    raise ValueError('dispatch: model index out of range')


@nb.njit(cache=True, inline="always")
def between(model, s, t):
    if model == 0:
        return ctrv.between(s, t)
    elif model == 1:
        return cv.between(s, t)
    elif model == 2:
        return se2r2.between(s, t)
    elif model == 3:
        return se2r3.between(s, t)
    elif model == 4:
        return se2se2.between(s, t)
    raise ValueError('dispatch: model index out of range')


@nb.njit(cache=True, inline="always")
def right_jacobian_inv(model, eps):
    if model == 0:
        return ctrv.right_jacobian_inv(eps)
    elif model == 1:
        return cv.right_jacobian_inv(eps)
    elif model == 2:
        return se2r2.right_jacobian_inv(eps)
    elif model == 3:
        return se2r3.right_jacobian_inv(eps)
    elif model == 4:
        return se2se2.right_jacobian_inv(eps)
    raise ValueError('dispatch: model index out of range')


@nb.njit(cache=True, inline="always")
def tangent_error(model, s, c):
    if model == 0:
        return ctrv.tangent_error(s, c)
    elif model == 1:
        return cv.tangent_error(s, c)
    elif model == 2:
        return se2r2.tangent_error(s, c)
    elif model == 3:
        return se2r3.tangent_error(s, c)
    elif model == 4:
        return se2se2.tangent_error(s, c)
    raise ValueError('dispatch: model index out of range')


@nb.njit(cache=True, inline="always")
def retract(model, s, eps):
    if model == 0:
        ctrv.retract(s, eps)
    elif model == 1:
        cv.retract(s, eps)
    elif model == 2:
        se2r2.retract(s, eps)
    elif model == 3:
        se2r3.retract(s, eps)
    elif model == 4:
        se2se2.retract(s, eps)


@nb.njit(cache=True, inline="always")
def common_of_state(model, s, p, c, Pc):
    if model == 0:
        ctrv.common_of_state(s, p, c, Pc)
    elif model == 1:
        cv.common_of_state(s, p, c, Pc)
    elif model == 2:
        se2r2.common_of_state(s, p, c, Pc)
    elif model == 3:
        se2r3.common_of_state(s, p, c, Pc)
    elif model == 4:
        se2se2.common_of_state(s, p, c, Pc)


@nb.njit(cache=True, inline="always")
def state_of_common(model, c, Pc, s, p):
    if model == 0:
        ctrv.state_of_common(c, Pc, s, p)
    elif model == 1:
        cv.state_of_common(c, Pc, s, p)
    elif model == 2:
        se2r2.state_of_common(c, Pc, s, p)
    elif model == 3:
        se2r3.state_of_common(c, Pc, s, p)
    elif model == 4:
        se2se2.state_of_common(c, Pc, s, p)


@nb.njit(cache=True, inline="always")
def between_add(model, s, t, w, acc):
    if model == 0:
        ctrv.between_add(s, t, w, acc)
    elif model == 1:
        cv.between_add(s, t, w, acc)
    elif model == 2:
        se2r2.between_add(s, t, w, acc)
    elif model == 3:
        se2r3.between_add(s, t, w, acc)
    elif model == 4:
        se2se2.between_add(s, t, w, acc)


@nb.njit(cache=True, inline="always")
def mix_transport(model, s, t, pt, w, acc):
    if model == 0:
        ctrv.mix_transport(s, t, pt, w, acc)
    elif model == 1:
        cv.mix_transport(s, t, pt, w, acc)
    elif model == 2:
        se2r2.mix_transport(s, t, pt, w, acc)
    elif model == 3:
        se2r3.mix_transport(s, t, pt, w, acc)
    elif model == 4:
        se2se2.mix_transport(s, t, pt, w, acc)


@nb.njit(cache=True, inline="always")
def state_from_physical_into(model, x, out):
    if model == 0:
        ctrv.state_from_physical_into(x, out)
    elif model == 1:
        cv.state_from_physical_into(x, out)
    elif model == 2:
        se2r2.state_from_physical_into(x, out)
    elif model == 3:
        se2r3.state_from_physical_into(x, out)
    elif model == 4:
        se2se2.state_from_physical_into(x, out)


@nb.njit(cache=True, inline="always")
def between_into(model, s, t, out):
    if model == 0:
        ctrv.between_into(s, t, out)
    elif model == 1:
        cv.between_into(s, t, out)
    elif model == 2:
        se2r2.between_into(s, t, out)
    elif model == 3:
        se2r3.between_into(s, t, out)
    elif model == 4:
        se2se2.between_into(s, t, out)


@nb.njit(cache=True, inline="always")
def right_jacobian_inv_into(model, eps, out):
    if model == 0:
        ctrv.right_jacobian_inv_into(eps, out)
    elif model == 1:
        cv.right_jacobian_inv_into(eps, out)
    elif model == 2:
        se2r2.right_jacobian_inv_into(eps, out)
    elif model == 3:
        se2r3.right_jacobian_inv_into(eps, out)
    elif model == 4:
        se2se2.right_jacobian_inv_into(eps, out)


@nb.njit(cache=True, inline="always")
def common_to_state_into(model, c, out):
    if model == 0:
        ctrv.common_to_state_into(c, out)
    elif model == 1:
        cv.common_to_state_into(c, out)
    elif model == 2:
        se2r2.common_to_state_into(c, out)
    elif model == 3:
        se2r3.common_to_state_into(c, out)
    elif model == 4:
        se2se2.common_to_state_into(c, out)


@nb.njit(cache=True, inline="always")
def common_jacobian_into(model, c, out):
    if model == 0:
        ctrv.common_jacobian_into(c, out)
    elif model == 1:
        cv.common_jacobian_into(c, out)
    elif model == 2:
        se2r2.common_jacobian_into(c, out)
    elif model == 3:
        se2r3.common_jacobian_into(c, out)
    elif model == 4:
        se2se2.common_jacobian_into(c, out)


@nb.njit(cache=True, inline="always")
def physical_to_common_into(model, x, out):
    if model == 0:
        ctrv.physical_to_common_into(x, out)
    elif model == 1:
        cv.physical_to_common_into(x, out)
    elif model == 2:
        se2r2.physical_to_common_into(x, out)
    elif model == 3:
        se2r3.physical_to_common_into(x, out)
    elif model == 4:
        se2se2.physical_to_common_into(x, out)


@nb.njit(cache=True, inline="always")
def physical_to_common_jacobian_into(model, x, out):
    if model == 0:
        ctrv.physical_to_common_jacobian_into(x, out)
    elif model == 1:
        cv.physical_to_common_jacobian_into(x, out)
    elif model == 2:
        se2r2.physical_to_common_jacobian_into(x, out)
    elif model == 3:
        se2r3.physical_to_common_jacobian_into(x, out)
    elif model == 4:
        se2se2.physical_to_common_jacobian_into(x, out)


@nb.njit(cache=True, inline="always")
def physical_into(model, s, out):
    if model == 0:
        ctrv.physical_into(s, out)
    elif model == 1:
        cv.physical_into(s, out)
    elif model == 2:
        se2r2.physical_into(s, out)
    elif model == 3:
        se2r3.physical_into(s, out)
    elif model == 4:
        se2se2.physical_into(s, out)


@nb.njit(cache=True, inline="always")
def calH_pose_into(model, s, out):
    if model == 0:
        ctrv.calH_pose_into(s, out)
    elif model == 2:
        se2r2.calH_pose_into(s, out)
    elif model == 3:
        se2r3.calH_pose_into(s, out)
    elif model == 4:
        se2se2.calH_pose_into(s, out)


@nb.njit(cache=True, inline="always")
def calH_position_into(model, s, out):
    if model == 0:
        ctrv.calH_position_into(s, out)
    elif model == 1:
        cv.calH_position_into(s, out)
    elif model == 2:
        se2r2.calH_position_into(s, out)
    elif model == 3:
        se2r3.calH_position_into(s, out)
    elif model == 4:
        se2se2.calH_position_into(s, out)


@nb.njit(cache=True, inline="always")
def between_add_at(model, ws, js, jt, w, jacc):
    if model == 0:
        ctrv.between_add_at(ws, js, jt, w, jacc)
    elif model == 1:
        cv.between_add_at(ws, js, jt, w, jacc)
    elif model == 2:
        se2r2.between_add_at(ws, js, jt, w, jacc)
    elif model == 3:
        se2r3.between_add_at(ws, js, jt, w, jacc)
    elif model == 4:
        se2se2.between_add_at(ws, js, jt, w, jacc)


@nb.njit(cache=True, inline="always")
def mix_transport_at(model, ws, js, jt, jpt, w, jacc):
    if model == 0:
        ctrv.mix_transport_at(ws, js, jt, jpt, w, jacc)
    elif model == 1:
        cv.mix_transport_at(ws, js, jt, jpt, w, jacc)
    elif model == 2:
        se2r2.mix_transport_at(ws, js, jt, jpt, w, jacc)
    elif model == 3:
        se2r3.mix_transport_at(ws, js, jt, jpt, w, jacc)
    elif model == 4:
        se2se2.mix_transport_at(ws, js, jt, jpt, w, jacc)


@nb.njit(cache=True, inline="always")
def retract_at(model, ws, js, jeps):
    if model == 0:
        ctrv.retract_at(ws, js, jeps)
    elif model == 1:
        cv.retract_at(ws, js, jeps)
    elif model == 2:
        se2r2.retract_at(ws, js, jeps)
    elif model == 3:
        se2r3.retract_at(ws, js, jeps)
    elif model == 4:
        se2se2.retract_at(ws, js, jeps)


@nb.njit(cache=True, inline="always")
def mix_on_group_at(model, ws, M, rw, rs, rp, rS, rPp, rd):
    if model == 0:
        return ctrv.mix_on_group_at(ws, M, rw, rs, rp, rS, rPp, rd)
    elif model == 1:
        return cv.mix_on_group_at(ws, M, rw, rs, rp, rS, rPp, rd)
    elif model == 2:
        return se2r2.mix_on_group_at(ws, M, rw, rs, rp, rS, rPp, rd)
    elif model == 3:
        return se2r3.mix_on_group_at(ws, M, rw, rs, rp, rS, rPp, rd)
    elif model == 4:
        return se2se2.mix_on_group_at(ws, M, rw, rs, rp, rS, rPp, rd)
    raise ValueError('dispatch: model index out of range')


@nb.njit(cache=True, inline="always")
def common_of_state_at(model, ws, js, jp, jc, jPc):
    if model == 0:
        ctrv.common_of_state_at(ws, js, jp, jc, jPc)
    elif model == 1:
        cv.common_of_state_at(ws, js, jp, jc, jPc)
    elif model == 2:
        se2r2.common_of_state_at(ws, js, jp, jc, jPc)
    elif model == 3:
        se2r3.common_of_state_at(ws, js, jp, jc, jPc)
    elif model == 4:
        se2se2.common_of_state_at(ws, js, jp, jc, jPc)


@nb.njit(cache=True, inline="always")
def state_of_common_at(model, ws, jc, jPc, js, jp):
    if model == 0:
        ctrv.state_of_common_at(ws, jc, jPc, js, jp)
    elif model == 1:
        cv.state_of_common_at(ws, jc, jPc, js, jp)
    elif model == 2:
        se2r2.state_of_common_at(ws, jc, jPc, js, jp)
    elif model == 3:
        se2r3.state_of_common_at(ws, jc, jPc, js, jp)
    elif model == 4:
        se2se2.state_of_common_at(ws, jc, jPc, js, jp)


@nb.njit(cache=True, inline="always")
def step_ll_pose(model, ws, js, jp, dt, jq, jz, jr):
    if model == 0:
        return ctrv.step_ll_pose(ws, js, jp, dt, ws[jq, 0], ws[jq, 1], ws[jz, 0], ws[jz, 1], ws[jz, 2], ws[jr, 0], ws[jr, 1], ws[jr, 2])
    elif model == 2:
        return se2r2.step_ll_pose(ws, js, jp, dt, ws[jq, 0], ws[jq, 1], ws[jz, 0], ws[jz, 1], ws[jz, 2], ws[jr, 0], ws[jr, 1], ws[jr, 2])
    elif model == 3:
        return se2r3.step_ll_pose(ws, js, jp, dt, ws[jq, 0], ws[jq, 1], ws[jq, 2], ws[jz, 0], ws[jz, 1], ws[jz, 2], ws[jr, 0], ws[jr, 1], ws[jr, 2])
    elif model == 4:
        return se2se2.step_ll_pose(ws, js, jp, dt, ws[jq, 0], ws[jq, 1], ws[jq, 2], ws[jz, 0], ws[jz, 1], ws[jz, 2], ws[jr, 0], ws[jr, 1], ws[jr, 2])
    raise ValueError('dispatch: model index out of range')


@nb.njit(cache=True, inline="always")
def step_ll_position(model, ws, js, jp, dt, jq, jz, jr):
    if model == 0:
        return ctrv.step_ll_position(ws, js, jp, dt, ws[jq, 0], ws[jq, 1], ws[jz, 0], ws[jz, 1], ws[jr, 0])
    elif model == 1:
        return cv.step_ll_position(ws, js, jp, dt, ws[jq, 0], ws[jz, 0], ws[jz, 1], ws[jr, 0])
    elif model == 2:
        return se2r2.step_ll_position(ws, js, jp, dt, ws[jq, 0], ws[jq, 1], ws[jz, 0], ws[jz, 1], ws[jr, 0])
    elif model == 3:
        return se2r3.step_ll_position(ws, js, jp, dt, ws[jq, 0], ws[jq, 1], ws[jq, 2], ws[jz, 0], ws[jz, 1], ws[jr, 0])
    elif model == 4:
        return se2se2.step_ll_position(ws, js, jp, dt, ws[jq, 0], ws[jq, 1], ws[jq, 2], ws[jz, 0], ws[jz, 1], ws[jr, 0])
    raise ValueError('dispatch: model index out of range')

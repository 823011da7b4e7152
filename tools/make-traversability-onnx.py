#!/usr/bin/env python3
"""Writes configs/models/traversability-cnn.onnx: SMUG's own small test CNN for the
`onnx` traversability plugin (configs/lunar-onnx.toml), with the `onnx` package only.

Three 3 x 3 convolutions with fixed weights (no training, nothing random), so the file is
the same on every run:
  1. four Sobel filters (+x, -x, +y, -y), scaled to rise per cell, then ReLU: the
     positive and negative parts of the gradient;
  2. their sum averaged over 3 x 3 (an L1 slope, smoothed), then ReLU;
  3. sigmoid(6 - 15 * slope / resolution) at the centre: ~1 on flat ground, 0.5 at an
     L1 slope of 0.4, ~0 on stones' flanks.
Input [1, 1, H, W] float32 elevation in metres (H, W free), output [1, 1, H, W];
'same' zero padding, receptive radius 3 cells (the plugin's `overlap` must be >= 3).

Usage: python3 tools/make-traversability-onnx.py [OUT.onnx] [--resolution 0.1]
       python3 tools/make-traversability-onnx.py --bad-models DIR
The second form writes the broken models the plugin's tests refuse: `rank3.onnx` (input
[1, H, W]) and `nan.onnx` (NaN everywhere: sqrt(-1 - |x|)).
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np
import onnx
from onnx import TensorProto, helper, numpy_helper

REPO = Path(__file__).resolve().parents[1]
DEFAULT_OUT = REPO / "configs" / "models" / "traversability-cnn.onnx"


def weights(resolution: float) -> dict[str, np.ndarray]:
    """The three layers' weights and biases."""
    sobel_x = np.array([[-1, 0, 1], [-2, 0, 2], [-1, 0, 1]], dtype=np.float32) / 8.0
    sobel_y = sobel_x.T  # rows run along +y (row 0 at the smallest y)
    w1 = np.stack([sobel_x, -sobel_x, sobel_y, -sobel_y])[:, None, :, :]
    w2 = np.full((1, 4, 3, 3), 1.0 / 9.0, dtype=np.float32)
    w3 = np.zeros((1, 1, 3, 3), dtype=np.float32)
    w3[0, 0, 1, 1] = -15.0 / resolution
    return {
        "w1": w1.astype(np.float32),
        "b1": np.zeros(4, dtype=np.float32),
        "w2": w2,
        "b2": np.zeros(1, dtype=np.float32),
        "w3": w3,
        "b3": np.array([6.0], dtype=np.float32),
    }


def model(resolution: float) -> onnx.ModelProto:
    """The network as an ONNX model (opset 13)."""
    conv = dict(kernel_shape=[3, 3], pads=[1, 1, 1, 1])
    nodes = [
        helper.make_node("Conv", ["elevation", "w1", "b1"], ["c1"], **conv),
        helper.make_node("Relu", ["c1"], ["r1"]),
        helper.make_node("Conv", ["r1", "w2", "b2"], ["c2"], **conv),
        helper.make_node("Relu", ["c2"], ["r2"]),
        helper.make_node("Conv", ["r2", "w3", "b3"], ["c3"], **conv),
        helper.make_node("Sigmoid", ["c3"], ["traversability"]),
    ]
    init = [numpy_helper.from_array(v, name=k) for k, v in weights(resolution).items()]
    graph = helper.make_graph(
        nodes,
        "smug-traversability-cnn",
        [helper.make_tensor_value_info("elevation", TensorProto.FLOAT, [1, 1, "H", "W"])],
        [helper.make_tensor_value_info("traversability", TensorProto.FLOAT, [1, 1, "H", "W"])],
        initializer=init,
    )
    m = helper.make_model(
        graph,
        producer_name="smug tools/make-traversability-onnx.py",
        opset_imports=[helper.make_opsetid("", 13)],
    )
    m.ir_version = 8
    onnx.checker.check_model(m)
    return m


def bad_models() -> dict[str, onnx.ModelProto]:
    """Models SMUG must refuse with a clear reason."""
    def wrap(name, nodes, in_shape, out_shape, init=()):
        graph = helper.make_graph(
            nodes,
            name,
            [helper.make_tensor_value_info("x", TensorProto.FLOAT, in_shape)],
            [helper.make_tensor_value_info("y", TensorProto.FLOAT, out_shape)],
            initializer=list(init),
        )
        m = helper.make_model(graph, opset_imports=[helper.make_opsetid("", 13)])
        m.ir_version = 8
        onnx.checker.check_model(m)
        return m

    minus_one = numpy_helper.from_array(np.array([-1.0], dtype=np.float32), name="m1")
    return {
        "rank3.onnx": wrap("rank3", [helper.make_node("Sigmoid", ["x"], ["y"])], [1, "H", "W"], [1, "H", "W"]),
        "nan.onnx": wrap(
            "nan",
            [
                helper.make_node("Abs", ["x"], ["a"]),
                helper.make_node("Sub", ["m1", "a"], ["s"]),
                helper.make_node("Sqrt", ["s"], ["y"]),
            ],
            [1, 1, "H", "W"],
            [1, 1, "H", "W"],
            [minus_one],
        ),
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", nargs="?", type=Path, default=DEFAULT_OUT)
    parser.add_argument("--resolution", type=float, default=0.1, help="training cell size, m")
    parser.add_argument("--bad-models", type=Path, help="write the broken test models here")
    args = parser.parse_args()
    if args.bad_models is not None:
        args.bad_models.mkdir(parents=True, exist_ok=True)
        for name, m in bad_models().items():
            onnx.save(m, str(args.bad_models / name))
            print(f"wrote {args.bad_models / name}")
        return
    args.out.parent.mkdir(parents=True, exist_ok=True)
    onnx.save(model(args.resolution), str(args.out))
    print(f"wrote {args.out} ({args.out.stat().st_size} bytes)")


if __name__ == "__main__":
    main()

"""The core layer: the model registry (from the generated table), filters, the batch engine, covariance
storage, argument checks and the common coordinates. Imports only ``lgekf.generated`` and numpy."""

"""One colour per integrator, shared by the plots of apps/bench (plot_pareto.py, plot_stability.py)."""
COLOURS = {
    "ExplicitEuler": "tab:gray",
    "SymplecticEuler": "tab:orange",
    "RungeKutta4": "tab:blue",
    "ImplicitEuler": "tab:red",
    "ImplicitMidpoint": "tab:green",
    # "solve": "newton"; the plain names are the linearized default
    "ImplicitEuler/newton": "tab:brown",
    "ImplicitMidpoint/newton": "tab:olive",
}

//! The canonical text and cache key of one spec of every kind, of every FAST spatial and
//! temporal filter and of every sample space, pinned: a change to the canonical text re-keys
//! every cache (committed ones included), so it must be a visible, deliberate break (bump the
//! pins and say so in CHANGELOG.md).

use build_assets::cache::key;
use noisebake_test_support::bake::spec;

const PINS: &[(&str, &str, &str)] = &[
    (
        "kind = \"sampler\"\ndims = [128, 128]",
        "kind=sampler;dims=[128,128];seed=0;format=u16;spp=1;sample_dims=2;spatial_filter={kind=gauss,sigma=1};frames=1",
        "e7aa8d727c669e2c60cc0e82ef9d8333",
    ),
    (
        "kind = \"sampler\"\ndims = [64, 32]\nseed = 3\nspp = 16\nsample_dims = 5\nspatial_filter = { kind = \"box\", size = 5 }\nframes = 4",
        "kind=sampler;dims=[64,32];seed=3;format=u16;spp=16;sample_dims=5;spatial_filter={kind=box,size=5};frames=4",
        "5ab24a52257a25d70df70291e8d53a93",
    ),
    (
        "kind = \"blue2d\"\ndims = [64, 64]",
        "kind=blue2d;dims=[64,64];seed=0;format=u8;sigma=1.5;initial_density=0.1",
        "d9c17c6902a43d0d127230ae2d42a4a4",
    ),
    (
        "kind = \"stbn\"\ndims = [64, 64, 16]\nseed = 7\nformat = \"u16\"",
        "kind=stbn;dims=[64,64,16];seed=7;format=u16;sigma_xy=1.9;sigma_t=1.9;initial_density=0.1;histogram=volume",
        "3fae75c4eae36d43877efc3dd7273be6",
    ),
    (
        "kind = \"stbn\"\ndims = [32, 32, 8]\nhistogram = \"slice\"\nsigma_xy = 2.1\nsigma_t = 1.5\ninitial_density = 0.2",
        "kind=stbn;dims=[32,32,8];seed=0;format=u8;sigma_xy=2.1;sigma_t=1.5;initial_density=0.2;histogram=slice",
        "bb9e42782560f9c07aed9a1f14ee82eb",
    ),
    (
        "kind = \"vac\"\ndims = [8, 8, 4, 4]\ngroups = [{ axes = [0, 1] }, { axes = [2], sigma = 1.5 }, { axes = [3] }]\ntoroidal = [true, true, false, true]\nformat = \"f32\"",
        "kind=vac;dims=[8,8,4,4];seed=0;format=f32;groups=[{axes=[0,1],sigma=1.9},{axes=[2],sigma=1.5},{axes=[3],sigma=1.9}];toroidal=[true,true,false,true];initial_density=0.1;histogram=volume",
        "edf914fa172df721cf815c1c69b08b82",
    ),
    (
        "kind = \"white\"\ndims = [16, 16, 4]\nseed = 3",
        "kind=white;dims=[16,16,4];seed=3;format=u8",
        "0f7cf9cd84cfb97c57bff78070a7f015",
    ),
    (
        "kind = \"independent2d\"\ndims = [32, 32, 8]",
        "kind=independent2d;dims=[32,32,8];seed=0;format=u8;sigma=1.9;initial_density=0.1",
        "be45641cecf1af043348a2b7384373ea",
    ),
    (
        "kind = \"golden\"\ndims = [32, 32, 8]\nformat = \"u16\"",
        "kind=golden;dims=[32,32,8];seed=0;format=u16;sigma=1.9;initial_density=0.1",
        "3a3f4a2e73cc96405ea309c3b670bcfe",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32]",
        "kind=fast;dims=[32,32];seed=0;format=u8;sample_space=scalar;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=none};combine=product;iterations=converged;start=ign",
        "6ad71d9ac3fb3551e65c303bd3561d06",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]",
        "kind=fast;dims=[32,32,8];seed=0;format=u8;sample_space=scalar;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=ign",
        "8f0c0f182a300f006e334aa4e690823c",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nspatial_filter = { kind = \"box\", size = 3 }\ntemporal_filter = { kind = \"box\", size = 4 }",
        "kind=fast;dims=[32,32,8];seed=0;format=u8;sample_space=scalar;distribution=uniform;spatial_filter={kind=box,size=3};temporal_filter={kind=box,size=4};combine=product;iterations=converged;start=ign",
        "dbc8693e7953dbcd0b1c445288dd2180",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 16]\nspatial_filter = { kind = \"binomial\", order = 2 }\ntemporal_filter = { kind = \"gauss\", sigma = 1.2 }",
        "kind=fast;dims=[32,32,16];seed=0;format=u8;sample_space=scalar;distribution=uniform;spatial_filter={kind=binomial,order=2};temporal_filter={kind=gauss,sigma=1.2};combine=product;iterations=converged;start=ign",
        "b2c422b952a1cd35af5c5e520dd19b64",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nspatial_filter = { kind = \"none\" }\ntemporal_filter = { kind = \"ema\", alpha = 0.1, beta = 0.1 }\ncombine = { separate = 0.5 }",
        "kind=fast;dims=[32,32,8];seed=0;format=u8;sample_space=scalar;distribution=uniform;spatial_filter={kind=none};temporal_filter={kind=ema,alpha=0.1,beta=0.1};combine={separate=0.5};iterations=converged;start=ign",
        "9bb1bc98317e4116ed310cc26dc7b722",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\ntemporal_filter = { kind = \"none\" }\niterations = 5\nstart = \"random\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8;sample_space=scalar;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=none};combine=product;iterations=5;start=random",
        "364f21d75e325fb102b5f4be9127b1c3",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\ntemporal_filter = { kind = \"taa\" }",
        "kind=fast;dims=[32,32,8];seed=0;format=u8;sample_space=scalar;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=taa,alpha=0.1,coverage=0.2,motion=[0,0],moving=0};combine=product;iterations=converged;start=ign",
        "cec2d1717cfea9046706cb8001463169",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\ntemporal_filter = { kind = \"taa\", motion = [3, -1] }",
        "kind=fast;dims=[32,32,8];seed=0;format=u8;sample_space=scalar;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=taa,alpha=0.1,coverage=0.2,motion=[3,-1],moving=0.25};combine=product;iterations=converged;start=ign",
        "570d6f806b0c69858c0f1740b62e519d",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\ndistribution = \"tent\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8;sample_space=scalar;distribution=tent;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=ign",
        "05f30e1895a02fd026d0d0d87940d551",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\ndistribution = \"gauss\"\nformat = \"f32\"",
        "kind=fast;dims=[32,32,8];seed=0;format=f32;sample_space=scalar;distribution=gauss;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=ign",
        "091904fe34d717bfd5d3e41fae653ae7",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"circle\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8;sample_space=circle;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=ign",
        "f5ea27f2f6cd12ac5c9c395a7d72c08c",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"vec2\"\nformat = \"u8x2\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8x2;sample_space=vec2;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=rd_ign_r2",
        "bbb0ca36f9327268fe25c2bed7da8338",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"vec3\"\nformat = \"u8x3\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8x3;sample_space=vec3;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=random",
        "2bd929c452a837e25ae99166fb223c47",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"vec4\"\nformat = \"u8x4\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8x4;sample_space=vec4;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=random",
        "e67bec0af321702dcd8c2edcb42b387f",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"sphere\"\nformat = \"u8x3\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8x3;sample_space=sphere;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=rd_ign_r2",
        "ac03792326dd5291946f1c0a7b10b26e",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"hemisphere\"\nformat = \"f32x3\"",
        "kind=fast;dims=[32,32,8];seed=0;format=f32x3;sample_space=hemisphere;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=rd_ign_r2",
        "d049e86685cf419c50497d3b91c98733",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"cosine_hemisphere\"\nformat = \"u8x3\"\nspatial_filter = { kind = \"box\", size = 5 }",
        "kind=fast;dims=[32,32,8];seed=0;format=u8x3;sample_space=cosine_hemisphere;distribution=uniform;spatial_filter={kind=box,size=5};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=ign_r2",
        "2a5b874d6a977112b66f36206c220995",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"cosine_hemisphere\"\nformat = \"u8x3\"\nstart = \"ign_r2\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8x3;sample_space=cosine_hemisphere;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=ign_r2",
        "d94cc3b503593792883eed9c1b06bce2",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"sphere\"\nformat = \"u8x3\"\nstart = \"rd_ign_r2\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8x3;sample_space=sphere;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=rd_ign_r2",
        "ac03792326dd5291946f1c0a7b10b26e",
    ),
];

#[test]
fn canonical_texts_and_keys_are_pinned() {
    let mut got = String::new();
    for (body, _, _) in PINS {
        let s = spec(body);
        got += &format!(
            "    (\n        {body:?},\n        {:?},\n        {:?},\n    ),\n",
            s.canonical(),
            key(&s)
        );
    }
    if std::env::var_os("NOISEBAKE_PRINT_PINS").is_some() {
        println!("{got}");
    }
    for (body, text, k) in PINS {
        let s = spec(body);
        assert_eq!(s.canonical(), *text, "{body}");
        assert_eq!(key(&s), *k, "{body}");
    }
}

/// Defaults are filled in: a spec that writes every default out has the canonical text (and so
/// the key) of one that leaves them all out, and the name is not part of it.
#[test]
fn defaults_written_out_change_nothing() {
    for (short, long) in [
        (
            "kind = \"stbn\"\ndims = [16, 16, 4]",
            "kind = \"stbn\"\ndims = [16, 16, 4]\nseed = 0\nformat = \"u8\"\nsigma_xy = 1.9\nsigma_t = 1.9\ninitial_density = 0.1\nhistogram = \"volume\"",
        ),
        (
            "kind = \"fast\"\ndims = [16, 16, 4]",
            "kind = \"fast\"\ndims = [16, 16, 4]\nsample_space = \"scalar\"\ndistribution = \"uniform\"\nspatial_filter = { kind = \"gauss\", sigma = 1.3435 }\ntemporal_filter = { kind = \"ema\", alpha = 0.1, beta = 0 }\ncombine = \"product\"\nstart = \"ign\"",
        ),
    ] {
        assert_eq!(spec(short).canonical(), spec(long).canonical());
    }
    let renamed = build_assets::spec::parse_toml(
        "[[texture]]\nname = \"OTHER\"\nkind = \"white\"\ndims = [4]\n",
    )
    .unwrap()
    .textures
    .remove(0);
    assert_eq!(
        renamed.canonical(),
        spec("kind = \"white\"\ndims = [4]").canonical()
    );
}

/// Every pinned canonical text reads back to its spec: `to_spec` then `canonical` is the
/// identity, which is how `cache verify` knows an entry's text is this version's.
#[test]
fn canonical_text_reads_back() {
    for (_, text, _) in PINS {
        let back =
            build_assets::spec::canonical::to_spec(text).unwrap_or_else(|e| panic!("{text}: {e}"));
        assert_eq!(back.canonical(), *text);
    }
    // Text in the pre-0.1 Debug form does not.
    assert!(build_assets::spec::canonical::to_spec(
        "kind=fast;dims=[16,16,4];seed=0;format=u8;sample_space=scalar;distribution=Uniform;spatial=Gauss { sigma: 1.3435 }"
    )
    .is_err());
}
